// Output files of `soa` that lose nothing: every write checked (a full disk is an error, not
// a silent exit 0), files that appear complete or keep what they had, and never the scene.
#pragma once

#include <cstddef>
#include <string>

#include "json_out.hpp"
#include "soa/error.hpp"

namespace soa::cli {

/// An error about a file other than the scene, whose message begins with that file or the
/// option that names it ("traj.csv: line 3, column \"t\": ...", "--out view: ..."): it is
/// reported as it is, without the scene's name in front.
struct FileError : Error {
  using Error::Error;
};

/// An output that could not be written: "--out traj.csv: No space left on device". Its
/// message names the output, not the scene.
struct OutputError : FileError {
  using FileError::FileError;
};

/// Text to a file descriptor. The first \p hold bytes are kept back, so that an output of
/// normal size is written only once it is complete; beyond that it streams. Write errors are
/// remembered (failed()) and finish() throws OutputError("<name>: <reason>").
class FdSink : public Sink {
 public:
  FdSink(int fd, std::string name, std::size_t hold = std::size_t(16) << 20)
      : fd_(fd), name_(std::move(name)), hold_(hold) {}
  void write(const char* data, std::size_t n) override;
  /// Writes what is held; throws OutputError when any write failed.
  void finish();
  bool failed() const { return errno_ != 0; }
  [[noreturn]] void fail() const;
  const std::string& name() const { return name_; }

 private:
  void drain();
  int fd_;
  std::string name_;
  std::size_t hold_;
  std::string buf_;
  int errno_ = 0;
};

/// An output file that appears complete or not at all: it is written to a temporary file
/// beside \p path (".NAME.XXXXXX") and renamed onto \p path by commit(); the destructor
/// removes it when commit() was not reached, so the old \p path, if any, is kept. A target
/// that exists and is not a regular file (/dev/null, /dev/full, a FIFO) is written directly.
/// Refuses \p path when it is \p protect (same device and inode: another spelling of the
/// path, a symbolic or a hard link) or a directory. Messages begin with \p label ("--out
/// traj.csv").
class OutputFile {
 public:
  OutputFile(const std::string& path, const std::string& label, const std::string& protect);
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  FdSink& sink() { return sink_; }
  /// Flushes, syncs and closes the file, then renames it onto the target.
  void commit();
  const std::string& path() const { return path_; }

 private:
  std::string path_, tmp_;
  int fd_ = -1;
  int slot_ = -1;  // of the temporary in remove_temporaries()
  FdSink sink_;
  bool direct_ = false, committed_ = false;
};

/// Removes the temporary files of the OutputFiles not committed yet, by unlink(2) alone:
/// safe in a signal handler (a second Ctrl-C ends the program at once, leaving none).
void remove_temporaries() noexcept;

/// True when \p a and \p b exist and are the same file (device and inode).
bool same_file(const std::string& a, const std::string& b);

}  // namespace soa::cli
