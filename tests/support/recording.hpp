/// \file
/// The student's answers, recorded in one process and judged in another (make grade).
///
/// A checker's verdict is only as good as the process that computes it: code linked into it
/// can rewrite its memory or its output. So make grade runs every lesson twice:
///   1. the recording run: the checker linked with the student's code, each of the lesson's
///      functions reached through a recorder (tests/exercises/recording.awk, mode record)
///      that calls the student's function and appends what it returned, or threw, to a file
///      of the exercise (exercise_main's --record);
///   2. the judging run: the same checker, linked with no student code at all, each of the
///      lesson's functions a replayer (mode replay) that returns the next recorded answer
///      (exercise_main's --replay). The checker draws the same cases from the same seeds, so
///      it makes the same calls in the same order; its verdict is the exercise's.
/// What the student's code writes into the record can only change the answers it gives,
/// which is what the checker judges anyway. A record that ends early (the run stopped) or does
/// not match the calls the checker makes leaves the exercise unjudged: its status is then the
/// recording run's, never a pass.
///
/// One record a call: <u64 size of the rest><u32 size of the name><name><u8 outcome><payload>,
/// the outcome 0 (returned: the value, then each reference parameter the function writes),
/// 1 (threw soa::exercise::NotDone), 2 (soa::Error), 3 (another std::exception), 4 (anything
/// else); for 1-3 the payload is what() as a string. Numbers in the machine's own layout:
/// the record is read back on the same machine.
#pragma once

#include <unistd.h>

#include <Eigen/Core>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "not_done.hpp"
#include "soa/soa.hpp"

namespace soa::test::recording {

enum class Mode { off, record, replay };

/// The process's recording: off (make exercises, make test), recording into a file, or
/// replaying one.
struct Session {
  Mode mode = Mode::off;
  int fd = -1;            ///< record: the file the records are appended to
  std::string in;         ///< replay: the whole record file
  std::size_t pos = 0;    ///< replay: where the next record starts
  std::size_t calls = 0;  ///< replay: records read so far
  std::string unjudged;   ///< replay: why the verdict cannot stand, "" while it can
};
inline Session& session() {
  static Session s;
  return s;
}
inline void start_recording(int fd) {
  session().mode = Mode::record;
  session().fd = fd;
}
inline void start_replay(std::string bytes) {
  Session& s = session();
  s.mode = Mode::replay;
  s.in = std::move(bytes);
  s.pos = 0;
  s.calls = 0;
  s.unjudged.clear();
}
/// Replay: "" when every record was read and each matched its call, else why not.
inline std::string replay_verdict() {
  const Session& s = session();
  if (!s.unjudged.empty()) return s.unjudged;
  if (s.pos != s.in.size())
    return "the record has answers to calls the checker never made (after " +
           std::to_string(s.calls) + " calls)";
  return "";
}

/// Thrown by a replayer that cannot give the call its answer: the exercise stays unjudged.
struct Unjudged {};

// ---- the layout of values ------------------------------------------------------------------

/// Reads a record's payload; any read past its end (a malformed record) leaves the exercise
/// unjudged.
class Reader {
 public:
  Reader(const std::string& s, std::size_t begin, std::size_t end)
      : s_(s), pos_(begin), end_(end) {}
  void get(void* out, std::size_t n) {
    if (n > end_ - pos_) fail("a value runs past the end of its record");
    std::memcpy(out, s_.data() + pos_, n);
    pos_ += n;
  }
  std::size_t left() const { return end_ - pos_; }
  bool done() const { return pos_ == end_; }
  [[noreturn]] static void fail(const std::string& why) {
    if (session().unjudged.empty()) session().unjudged = why;
    throw Unjudged{};
  }

 private:
  const std::string& s_;
  std::size_t pos_, end_;
};

inline void put(std::string& o, const void* p, std::size_t n) {
  o.append(static_cast<const char*>(p), n);
}
/// A count of things of \p bytes each, no more than the record still holds.
inline std::uint64_t get_count(Reader& r, std::size_t bytes) {
  std::uint64_t n = 0;
  r.get(&n, sizeof n);
  if (bytes > 0 && n > r.left() / bytes) Reader::fail("a size larger than its record");
  return n;
}

// Every overload declared first, so that each template below finds the others.
template <class T>
std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> encode(std::string& o, const T& v);
template <class T>
std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> decode(Reader& r, T& v);
template <class S, int R, int C, int O, int MR, int MC>
void encode(std::string& o, const Eigen::Matrix<S, R, C, O, MR, MC>& m);
template <class S, int R, int C, int O, int MR, int MC>
void decode(Reader& r, Eigen::Matrix<S, R, C, O, MR, MC>& m);
template <class T, class A>
void encode(std::string& o, const std::vector<T, A>& v);
template <class T, class A>
void decode(Reader& r, std::vector<T, A>& v);
inline void encode(std::string& o, const std::vector<bool>& v);
inline void decode(Reader& r, std::vector<bool>& v);
inline void encode(std::string& o, const std::string& s);
inline void decode(Reader& r, std::string& s);
inline void decode(Reader& r, bool& b);

/// A struct recorded member by member: Members<T>::list() is the tuple of its members'
/// pointers, in order. The library's are here; a lesson's are written by recording.sh.
template <class T>
struct Members : std::false_type {};
template <class S>
struct Members<StateT<S>> : std::true_type {
  static auto list() { return std::make_tuple(&StateT<S>::theta, &StateT<S>::beta); }
};
template <class S>
struct Members<FreeBodyStateT<S>> : std::true_type {
  static auto list() {
    return std::make_tuple(&FreeBodyStateT<S>::q, &FreeBodyStateT<S>::r, &FreeBodyStateT<S>::V);
  }
};
template <class S>
struct Members<FreeBodyRateT<S>> : std::true_type {
  static auto list() {
    return std::make_tuple(&FreeBodyRateT<S>::omega, &FreeBodyRateT<S>::r_dot,
                           &FreeBodyRateT<S>::V_dot);
  }
};
template <class T>
std::enable_if_t<Members<T>::value> encode(std::string& o, const T& v);
template <class T>
std::enable_if_t<Members<T>::value> decode(Reader& r, T& v);

/// The library's value classes hold fixed-size Eigen members and scalars only: their bytes
/// are the value.
template <class T>
struct Flat : std::false_type {};
template <class S, class K>
struct Flat<SpatialVector<S, K>> : std::true_type {};
template <class S>
struct Flat<PhiT<S>> : std::true_type {};
template <class S>
struct Flat<SpatialInertiaT<S>> : std::true_type {};
template <class S>
struct Flat<UnitQuaternionT<S>> : std::true_type {};
template <class S>
struct Flat<PoseT<S>> : std::true_type {};
template <class T>
std::enable_if_t<Flat<T>::value> encode(std::string& o, const T& v) {
  put(o, static_cast<const void*>(&v), sizeof v);
}
template <class T>
std::enable_if_t<Flat<T>::value> decode(Reader& r, T& v) {
  r.get(static_cast<void*>(&v), sizeof v);
}

template <class T>
std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> encode(std::string& o, const T& v) {
  put(o, &v, sizeof v);
}
template <class T>
std::enable_if_t<std::is_arithmetic_v<T> || std::is_enum_v<T>> decode(Reader& r, T& v) {
  r.get(&v, sizeof v);
}
/// A bool from any byte: a record's byte need not be 0 or 1.
inline void decode(Reader& r, bool& b) {
  unsigned char c = 0;
  r.get(&c, 1);
  b = c != 0;
}
template <class S, int R, int C, int O, int MR, int MC>
void encode(std::string& o, const Eigen::Matrix<S, R, C, O, MR, MC>& m) {
  const std::int64_t rows = m.rows(), cols = m.cols();
  put(o, &rows, sizeof rows);
  put(o, &cols, sizeof cols);
  put(o, m.data(), sizeof(S) * std::size_t(m.size()));
}
template <class S, int R, int C, int O, int MR, int MC>
void decode(Reader& r, Eigen::Matrix<S, R, C, O, MR, MC>& m) {
  std::int64_t rows = 0, cols = 0;
  r.get(&rows, sizeof rows);
  r.get(&cols, sizeof cols);
  if (rows < 0 || cols < 0 || (R != Eigen::Dynamic && rows != R) ||
      (C != Eigen::Dynamic && cols != C) || (MR != Eigen::Dynamic && rows > MR) ||
      (MC != Eigen::Dynamic && cols > MC) ||
      (cols > 0 && std::uint64_t(rows) > r.left() / sizeof(S) / std::uint64_t(cols)))
    Reader::fail("a matrix of a size it cannot have");
  m.resize(rows, cols);
  r.get(m.data(), sizeof(S) * std::size_t(m.size()));
}
template <class T, class A>
void encode(std::string& o, const std::vector<T, A>& v) {
  const std::uint64_t n = v.size();
  put(o, &n, sizeof n);
  for (const T& x : v) encode(o, x);
}
template <class T, class A>
void decode(Reader& r, std::vector<T, A>& v) {
  const std::uint64_t n = get_count(r, 1);  // every element takes a byte at least
  v.clear();
  v.resize(n);
  for (T& x : v) decode(r, x);
}
inline void encode(std::string& o, const std::vector<bool>& v) {
  const std::uint64_t n = v.size();
  put(o, &n, sizeof n);
  for (const bool b : v) o.push_back(b ? 1 : 0);
}
inline void decode(Reader& r, std::vector<bool>& v) {
  const std::uint64_t n = get_count(r, 1);
  v.assign(n, false);
  for (std::uint64_t i = 0; i < n; ++i) {
    char c = 0;
    r.get(&c, 1);
    v[i] = c != 0;
  }
}
inline void encode(std::string& o, const std::string& s) {
  const std::uint64_t n = s.size();
  put(o, &n, sizeof n);
  o += s;
}
inline void decode(Reader& r, std::string& s) {
  s.assign(get_count(r, 1), '\0');
  r.get(s.data(), s.size());
}
template <class T, class... M>
void encode_members(std::string& o, const T& v, M T::*... m) {
  (encode(o, v.*m), ...);
}
template <class T, class... M>
void decode_members(Reader& r, T& v, M T::*... m) {
  (decode(r, v.*m), ...);
}
template <class T>
std::enable_if_t<Members<T>::value> encode(std::string& o, const T& v) {
  std::apply([&](auto... m) { encode_members(o, v, m...); }, Members<T>::list());
}
template <class T>
std::enable_if_t<Members<T>::value> decode(Reader& r, T& v) {
  std::apply([&](auto... m) { decode_members(r, v, m...); }, Members<T>::list());
}

// ---- the calls -----------------------------------------------------------------------------

enum Outcome : std::uint8_t { kReturned, kNotDone, kError, kException, kOther };

inline void append(const char* name, Outcome outcome, const std::string& payload) {
  std::string rec;
  const std::uint32_t name_size = std::uint32_t(std::strlen(name));
  const std::uint64_t size = sizeof name_size + name_size + 1 + payload.size();
  put(rec, &size, sizeof size);
  put(rec, &name_size, sizeof name_size);
  rec.append(name, name_size);
  rec.push_back(char(outcome));
  rec += payload;
  // Written whole at once: a run that stops later leaves every earlier answer on file.
  std::size_t done = 0;
  while (done < rec.size()) {
    const ssize_t n = ::write(session().fd, rec.data() + done, rec.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // a broken record: the judging run will find it so
    done += std::size_t(n);
  }
}

/// The recorder of one of the student's functions: \p real calls it; what it returns (and
/// then each reference parameter in \p outs, which it writes) or throws is recorded, and
/// returned or thrown again.
template <class R, class F, class... Out>
R record(const char* name, F&& real, Out&... outs) {
  if (session().mode != Mode::record) return real();
  std::string payload;
  try {
    R value = real();
    encode(payload, value);
    (encode(payload, outs), ...);
    append(name, kReturned, payload);
    return value;
  } catch (const soa::exercise::NotDone& e) {
    encode(payload, std::string(e.what()));
    append(name, kNotDone, payload);
    throw;
  } catch (const soa::Error& e) {
    encode(payload, std::string(e.what()));
    append(name, kError, payload);
    throw;
  } catch (const std::exception& e) {
    encode(payload, std::string(e.what()));
    append(name, kException, payload);
    throw;
  } catch (...) {
    append(name, kOther, payload);
    throw;
  }
}

/// What the replayer throws for a recorded exception of another kind than ours.
struct OtherException {};

/// The replayer of one of the student's functions: the next record's answer, for a call of
/// \p name; its reference parameters \p outs written as the student's function wrote them.
template <class R, class... Out>
R replay(const char* name, Out&... outs) {
  Session& s = session();
  if (s.mode != Mode::replay || !s.unjudged.empty()) Reader::fail("no record to replay");
  std::uint64_t size = 0;
  std::uint32_t name_size = 0;
  Reader head(s.in, s.pos, s.in.size());
  if (head.left() == 0)
    Reader::fail("the record ends after " + std::to_string(s.calls) + " calls (the run stopped)");
  head.get(&size, sizeof size);
  if (size > head.left() || size < sizeof name_size + 1)
    Reader::fail("the record ends inside call " + std::to_string(s.calls + 1));
  const std::size_t begin = s.pos + sizeof size, end = begin + size;
  Reader r(s.in, begin, end);
  r.get(&name_size, sizeof name_size);
  if (name_size > r.left() || s.in.compare(begin + sizeof name_size, name_size, name) != 0 ||
      std::strlen(name) != name_size)
    Reader::fail("call " + std::to_string(s.calls + 1) + " of the record is not of " + name +
                 ", which the checker called");
  std::string skipped(name_size, '\0');
  r.get(skipped.data(), name_size);
  std::uint8_t outcome = 0;
  r.get(&outcome, 1);
  s.pos = end;
  ++s.calls;
  if (outcome == kReturned) {
    R value{};
    decode(r, value);
    (decode(r, outs), ...);
    if (!r.done()) Reader::fail("call " + std::to_string(s.calls) + " of the record is too long");
    return value;
  }
  std::string what;
  if (outcome != kOther) decode(r, what);
  if (!r.done()) Reader::fail("call " + std::to_string(s.calls) + " of the record is too long");
  switch (outcome) {
    case kNotDone: {
      // "not done: exercise <which> (its statement ...)"
      const std::string head_text = "not done: exercise ";
      std::string which = what.rfind(head_text, 0) == 0 ? what.substr(head_text.size()) : what;
      which = which.substr(0, which.find(" ("));
      throw soa::exercise::NotDone(which);
    }
    case kError:
      throw soa::Error(what);
    case kException:
      throw std::runtime_error(what);
    case kOther:
      throw OtherException{};
    default:
      Reader::fail("call " + std::to_string(s.calls) + " of the record has an unknown outcome");
  }
}

}  // namespace soa::test::recording
