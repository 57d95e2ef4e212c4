// The viewer's folder: the page, three.js and data.js written so that nothing is lost on bad
// input (a project rule): everything that can be refused is refused before the folder is
// touched; a folder is reused only when it holds nothing but a viewer's files; each file is
// written beside its place and renamed into it only when all six are complete; writers of
// the same folder take turns (an exclusive flock(2) on the folder), so that the folder holds
// the six files of one of them.
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "detail.hpp"

#ifndef SOA_THREE_DIR
#define SOA_THREE_DIR "/usr/share/javascript/three"
#endif

namespace soa::view {
namespace {

namespace fs = std::filesystem;

/// The files of a viewer's folder besides the page's (detail::kPageFiles).
const char* const kOtherFiles[] = {"three.min.js", "OrbitControls.js", "data.js"};

/// Where \p name is written before it is renamed into place (a left-over one, from a write
/// that was killed, is the viewer's too: it is replaced).
std::string temporary_name(const std::string& name) {
  return "." + name + ".soa-view-tmp";
}

bool is_viewer_entry(const std::string& entry) {
  auto is = [&](const std::string& f) { return entry == f || entry == temporary_name(f); };
  for (std::size_t i = 0; i < detail::kPageFileCount; ++i)
    if (is(detail::kPageFiles[i].name)) return true;
  for (const char* f : kOtherFiles)
    if (is(f)) return true;
  return false;
}

std::string system_error(int e) {
  return std::strerror(e);
}

/// The whole of a file of three.js.
std::string read_three(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw Error("three.js not found: " + path.string() + " (Debian package libjs-three)");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  if (in) s << in.rdbuf();
  if (!in || in.bad() || !s) throw Error(path.string() + ": cannot read the file");
  return s.str();
}

/// Refuses a folder that is not one, or that holds anything but a viewer's files.
void check_folder(const fs::path& dir) {
  std::error_code ec;
  const fs::file_status st = fs::status(dir, ec);
  if (!fs::exists(st)) return;
  if (!fs::is_directory(st))
    throw Error(dir.string() + ": exists and is not a folder (the viewer is a folder of files)");
  fs::directory_iterator it(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot read the folder (" + ec.message() + ")");
  for (; it != fs::directory_iterator(); it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!is_viewer_entry(name))
      throw Error(dir.string() + ": holds \"" + name +
                  "\", which is not a file of the viewer; give a new folder, an empty one, or "
                  "one the viewer was written to before");
    if (!it->is_regular_file(ec) || it->is_symlink(ec))
      throw Error(dir.string() + ": \"" + name + "\" is not a plain file; give another folder");
  }
  if (ec) throw Error(dir.string() + ": cannot read the folder (" + ec.message() + ")");
}

/// Creates \p dir and its missing parents; remembers which, to remove them on failure.
std::vector<fs::path> create_folder(const fs::path& dir) {
  std::vector<fs::path> created;
  std::error_code ec;
  for (fs::path p = dir; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
    created.insert(created.begin(), p);
    if (p == p.parent_path()) break;
  }
  for (const fs::path& p : created)
    if (!fs::create_directory(p, ec) && ec)
      throw Error(dir.string() + ": cannot create the folder (" + ec.message() + ")");
  return created;
}

/// A file being written to its temporary name; every write checked.
class TempFile : public detail::Sink {
 public:
  TempFile(const fs::path& dir, const std::string& name)
      : target_(dir / name), shown_(target_.string()), temp_(dir / temporary_name(name)) {
    ::unlink(temp_.c_str());  // a left-over of a killed write: ours
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0644);
    if (fd_ < 0) fail(errno);
  }
  ~TempFile() override {
    if (fd_ >= 0) ::close(fd_);
  }
  void write(const char* data, std::size_t n) override {
    while (n > 0) {
      const ssize_t w = ::write(fd_, data, n);
      if (w < 0 && errno == EINTR) continue;
      if (w <= 0) fail(w < 0 ? errno : ENOSPC);
      data += w;
      n -= std::size_t(w);
    }
  }
  void close() {
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail(errno);  // a full disk may only say so now (NFS)
  }
  const fs::path& temp() const { return temp_; }
  const fs::path& target() const { return target_; }

 private:
  [[noreturn]] void fail(int e) const {
    throw Error(shown_ + ": cannot write the file (" + system_error(e) + ")");
  }
  fs::path target_;
  std::string shown_;
  fs::path temp_;
  int fd_ = -1;
};

/// An exclusive lock on a folder (flock(2) on the folder itself, nothing written in it),
/// held until destroyed. Taken on the folder that is at \p dir when it is granted: one
/// removed or replaced while this writer waited is not the one written to.
class FolderLock {
 public:
  explicit FolderLock(const fs::path& dir) {
    for (int attempt = 0; attempt < 100; ++attempt) {
      fd_ = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
      if (fd_ < 0)
        throw Error(dir.string() + ": cannot open the folder (" + system_error(errno) + ")");
      int r;
      while ((r = ::flock(fd_, LOCK_EX)) != 0 && errno == EINTR) {
      }
      if (r != 0)
        throw Error(dir.string() + ": cannot lock the folder (" + system_error(errno) + ")");
      struct stat held, now;
      if (::fstat(fd_, &held) == 0 && ::stat(dir.c_str(), &now) == 0 && held.st_dev == now.st_dev &&
          held.st_ino == now.st_ino)
        return;
      ::close(fd_);
      fd_ = -1;
      create_folder(dir);  // removed by the writer that held the lock (its write failed)
    }
    throw Error(dir.string() + ": the folder keeps being replaced; cannot lock it");
  }
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);  // releases the lock
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_ = -1;
};

/// Removes the temporaries, and the folders write() created, unless the write completed.
struct Cleanup {
  std::vector<std::pair<fs::path, fs::path>> temporaries;  // (temporary, its place)
  std::vector<fs::path> folders;
  bool done = false;
  ~Cleanup() {
    if (done) return;
    std::error_code ec;
    for (const auto& t : temporaries) fs::remove(t.first, ec);
    for (auto it = folders.rbegin(); it != folders.rend(); ++it) fs::remove(*it, ec);  // if empty
  }
};

}  // namespace

fs::path three_dir() {
  const char* env = std::getenv("SOA_THREE_DIR");
  return fs::path(env && *env ? env : SOA_THREE_DIR);
}

void check_destination(const fs::path& dir) {
  if (dir.empty()) throw Error("view: no folder to write the viewer to");
  const fs::path three = three_dir();
  read_three(three / "build" / "three.min.js");
  read_three(three / "examples" / "js" / "controls" / "OrbitControls.js");
  check_folder(dir);
}

void write(const View& view, const fs::path& dir) {
  // Everything that can be refused, before the folder is touched.
  if (dir.empty()) throw Error("view: no folder to write the viewer to");
  detail::check(view);
  const fs::path three = three_dir();
  const std::string three_min = read_three(three / "build" / "three.min.js");
  const std::string orbit = read_three(three / "examples" / "js" / "controls" / "OrbitControls.js");
  check_folder(dir);

  std::vector<fs::path> created = create_folder(dir);
  const FolderLock lock(dir);  // released after the cleanup below
  check_folder(dir);           // as another writer or the user left it
  Cleanup cleanup;
  cleanup.folders = std::move(created);
  auto put = [&](const std::string& name, const char* data, std::size_t n) {
    TempFile f(dir, name);
    cleanup.temporaries.emplace_back(f.temp(), f.target());
    f.write(data, n);
    f.close();
  };
  for (std::size_t i = 0; i < detail::kPageFileCount; ++i) {
    const detail::PageFile& p = detail::kPageFiles[i];
    put(p.name, reinterpret_cast<const char*>(p.data), p.size);
  }
  put("three.min.js", three_min.data(), three_min.size());
  put("OrbitControls.js", orbit.data(), orbit.size());
  {
    TempFile f(dir, "data.js");
    cleanup.temporaries.emplace_back(f.temp(), f.target());
    detail::write_data_js(view, f);
    f.close();
  }

  // All six are complete: into place.
  for (const auto& [temp, target] : cleanup.temporaries)
    if (std::rename(temp.c_str(), target.c_str()) != 0)
      throw Error(target.string() + ": cannot put the file in place (" + system_error(errno) + ")");
  cleanup.done = true;
}

}  // namespace soa::view
