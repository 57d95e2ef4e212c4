/// # A sample lesson
///
/// Prose with math, \f$V = [\omega; v]\f$, and a display:
/// \f[ V(y) = \phi^*(x,y)\, V(x). \f]
#include <cstdio>

int main() {
  /// Indented prose: the indentation and "/// " go.
  int a = 1;
  ///not prose: no space after the slashes
  //// not prose: four slashes
  int b = a + 1;  /// not prose: the line does not start with ///


  ///
  ///   - a nested list item keeps its own indentation

  /// Between two prose lines only blank code lines: no empty code block.
  std::printf("%d\n", b);

  return 0;
}
/// Trailing prose.
