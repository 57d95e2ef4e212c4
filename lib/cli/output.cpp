// Checked output: write(2) with its errors kept, temporary file and rename for --out.
#include "output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace soa::cli {
namespace {

// The temporary files of the OutputFiles alive, as fixed buffers a signal handler can read:
// a slot is in use while its first byte is not 0.
constexpr int kTemporaries = 8;
char g_temporary[kTemporaries][4096];

int hold_temporary(const std::string& path) {
  if (path.size() >= sizeof g_temporary[0]) return -1;
  for (int i = 0; i < kTemporaries; ++i)
    if (g_temporary[i][0] == '\0') {
      std::memcpy(g_temporary[i], path.c_str(), path.size() + 1);
      return i;
    }
  return -1;
}

void release_temporary(int slot) {
  if (slot >= 0) g_temporary[slot][0] = '\0';
}

}  // namespace

void remove_temporaries() noexcept {
  for (int i = 0; i < kTemporaries; ++i)
    if (g_temporary[i][0] != '\0') ::unlink(g_temporary[i]);
}

void FdSink::write(const char* data, std::size_t n) {
  if (errno_) return;
  buf_.append(data, n);
  if (buf_.size() >= hold_) {
    hold_ = std::size_t(1) << 20;  // streaming from now on, in pieces of a megabyte
    drain();
  }
}

void FdSink::drain() {
  std::size_t done = 0;
  while (done < buf_.size() && !errno_) {
    const ssize_t w = ::write(fd_, buf_.data() + done, buf_.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0)
      errno_ = w < 0 ? errno : EIO;
    else
      done += std::size_t(w);
  }
  buf_.clear();
}

void FdSink::finish() {
  drain();
  if (errno_) fail();
}

void FdSink::fail() const {
  throw OutputError(name_ + ": " + std::strerror(errno_));
}

bool same_file(const std::string& a, const std::string& b) {
  struct stat sa, sb;
  return ::stat(a.c_str(), &sa) == 0 && ::stat(b.c_str(), &sb) == 0 && sa.st_dev == sb.st_dev &&
         sa.st_ino == sb.st_ino;
}

OutputFile::OutputFile(const std::string& path, const std::string& label,
                       const std::string& protect)
    : path_(path), sink_(-1, label, std::size_t(1) << 20) {
  auto fail = [&](const std::string& why) { throw OutputError(label + ": " + why); };
  if (path.empty()) fail("empty file name");
  if (same_file(path, protect)) fail("is the scene file " + protect + "; refusing to overwrite it");
  struct stat st;
  if (::stat(path.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail("is a directory");
    direct_ = !S_ISREG(st.st_mode);
  }
  if (direct_) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd_ < 0) fail(std::strerror(errno));
  } else {
    const std::size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
    const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
    if (base.empty()) fail("is a directory");
    tmp_ = dir + "." + base + ".XXXXXX";
    std::vector<char> name(tmp_.begin(), tmp_.end());
    name.push_back('\0');
    fd_ = ::mkstemp(name.data());
    if (fd_ < 0) fail(std::string("cannot create a file there (") + std::strerror(errno) + ")");
    tmp_ = name.data();
    slot_ = hold_temporary(tmp_);
    const mode_t mask = ::umask(0);  // the mode a new file would get: 0666 less the umask
    ::umask(mask);
    ::fchmod(fd_, 0666 & ~mask);
  }
  sink_ = FdSink(fd_, label, std::size_t(1) << 20);
}

OutputFile::~OutputFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_ && !tmp_.empty()) ::unlink(tmp_.c_str());
  release_temporary(slot_);
}

void OutputFile::commit() {
  sink_.finish();
  auto fail = [&](int e) {
    errno = e;
    throw OutputError(sink_.name() + ": " + std::strerror(e));
  };
  if (!direct_ && ::fsync(fd_) != 0) fail(errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(errno);
  if (!direct_ && ::rename(tmp_.c_str(), path_.c_str()) != 0) fail(errno);
  committed_ = true;
  release_temporary(slot_);
  slot_ = -1;
}

}  // namespace soa::cli
