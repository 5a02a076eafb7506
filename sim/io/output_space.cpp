#include "io/output_space.hpp"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "core/error.hpp"
#include "core/format.hpp"

namespace bsmpm {

double free_disk_bytes(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path p = fs::absolute(path.empty() ? "." : path, error);
  if (error) return -1.0;
  while (!p.empty() && !fs::exists(p, error) && p != p.parent_path()) p = p.parent_path();
  struct statvfs s {};
  if (statvfs(p.c_str(), &s) != 0) return -1.0;
  return static_cast<double>(s.f_bavail) * static_cast<double>(s.f_frsize);
}

double file_size_limit_bytes() {
  rlimit limit{};
  if (getrlimit(RLIMIT_FSIZE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return HUGE_VAL;
  return static_cast<double>(limit.rlim_cur);
}

bool is_out_of_space(int error_number) {
  return error_number == ENOSPC || error_number == EDQUOT || error_number == EFBIG;
}

std::string describe_space(const std::string& path) {
  const double free = free_disk_bytes(path);
  std::string text = free >= 0.0 ? format_bytes(free) + " free on its disk" : "the free space unknown";
  const double limit = file_size_limit_bytes();
  if (std::isfinite(limit)) text += ", and a file may reach " + format_bytes(limit) + " (ulimit -f)";
  return text;
}

FileRoom::FileRoom(const std::string& path, const std::string& name) : path_(path), name_(name.empty() ? path : name) {
  fd_ = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd_ < 0) throw IoError(path + ": cannot open to reserve room: " + std::strerror(errno));
}

FileRoom::~FileRoom() {
  if (fd_ < 0) return;
  release();
  ::close(fd_);
}

FileRoom::FileRoom(FileRoom&& other) noexcept
    : path_(std::move(other.path_)),
      name_(std::move(other.name_)),
      fd_(other.fd_),
      reserved_end_(other.reserved_end_),
      size_when_reserved_(other.size_when_reserved_) {
  other.fd_ = -1;
}

FileRoom& FileRoom::operator=(FileRoom&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) {
      release();
      ::close(fd_);
    }
    path_ = std::move(other.path_);
    name_ = std::move(other.name_);
    fd_ = other.fd_;
    reserved_end_ = other.reserved_end_;
    size_when_reserved_ = other.size_when_reserved_;
    other.fd_ = -1;
  }
  return *this;
}

std::uint64_t FileRoom::size() const {
  struct stat s {};
  if (fstat(fd_, &s) != 0) throw IoError(path_ + ": cannot tell its size: " + std::strerror(errno));
  return static_cast<std::uint64_t>(s.st_size);
}

bool FileRoom::allocate(std::uint64_t from, std::uint64_t bytes) {
  while (true) {
    if (fallocate(fd_, FALLOC_FL_KEEP_SIZE, static_cast<off_t>(from), static_cast<off_t>(bytes)) == 0) return true;
    if (errno == EINTR) continue;
    if (is_out_of_space(errno)) return false;
    if (errno == EOPNOTSUPP || errno == ENOSYS) {
      // A file system that cannot allocate ahead (some network file systems): the free space
      // is the best there is, though another program may take it before the write.
      const double free = free_disk_bytes(path_);
      return free < 0.0 || free >= static_cast<double>(bytes);
    }
    throw IoError(path_ + ": cannot reserve room: " + std::strerror(errno));
  }
}

void FileRoom::keep(std::uint64_t bytes, const std::string& what) {
  const std::uint64_t end = size();
  // Allocated already, and the file has not changed length since (a writer that cuts its
  // file back, as HDF5 does to its allocated end, may have freed some of it).
  if (end == size_when_reserved_ && end + bytes <= reserved_end_) return;
  const double limit = file_size_limit_bytes();
  const auto fail = [&] {
    release();
    return OutOfSpaceError(name_ + ": no room for " + what + " (about " + format_bytes(static_cast<double>(bytes)) +
                               "): " + describe_space(path_),
                           true);
  };
  if (static_cast<double>(end + bytes) > limit) throw fail();
  // Twice what is asked when it fits (within the file-size limit), else just that.
  const std::uint64_t ample = static_cast<std::uint64_t>(std::min(2.0 * static_cast<double>(bytes), limit - end));
  size_when_reserved_ = end;
  if (ample > bytes && allocate(end, ample)) {
    reserved_end_ = end + ample;
    return;
  }
  if (allocate(end, bytes)) {
    reserved_end_ = end + bytes;
    return;
  }
  throw fail();
}

void FileRoom::release() {
  if (fd_ < 0 || reserved_end_ == 0) return;
  reserved_end_ = 0;
  // Cutting a file to its own length frees the blocks allocated beyond it (and a failed
  // fallocate may have left some there).
  struct stat s {};
  if (fstat(fd_, &s) == 0 && ftruncate(fd_, s.st_size) != 0) {
    // Nothing lost: the blocks stay the file's until it is cut or removed.
  }
}

}  // namespace bsmpm
