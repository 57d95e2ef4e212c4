/// \file
/// Text from a file (a name, a key, a value) as a message shows it: on one line, and
/// nothing a terminal would act on.
#pragma once

#include <string>

namespace soa {

/// \p text with what is not printable escaped: C0 controls as `\n`, `\r`, `\t` or `\x1b`,
/// DEL as `\x7f`, C1 controls and the line and paragraph separators as `\u0085`, `\u2028`,
/// and each byte that is not part of valid UTF-8 as `\xff`. Printable text, UTF-8 letters
/// included, is unchanged.
std::string printable(const std::string& text);

/// \p text is valid UTF-8 (RFC 3629: no overlong form, no surrogate, nothing above U+10FFFF).
bool is_utf8(const std::string& text);

}  // namespace soa
