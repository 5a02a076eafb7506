// Room on the disk for a run's output, taken before it is written. A write that fails half-way
// for lack of space leaves an HDF5 file whose superblock points past its end: unreadable, every
// frame in it lost (HDF5 1.10 writes its metadata in place; it has no journal). So the blocks
// the next frame will fill are allocated beforehand (fallocate with FALLOC_FL_KEEP_SIZE: the
// file keeps its length, the blocks are its own), the file-size limit of the process (ulimit
// -f) is checked against the same bytes, and a run that finds no room stops between two steps
// with every file whole (docs/output-format.md, "A full disk").
#pragma once

#include <cstdint>
#include <string>

namespace bsmpm {

// Free space for this user on the file system holding `path` (or its nearest existing
// parent), in bytes; negative when unknown.
double free_disk_bytes(const std::string& path);

// The size a file of this process may reach (RLIMIT_FSIZE, soft), in bytes; infinite without
// a limit.
double file_size_limit_bytes();

// Whether a failed write's errno means that the room ran out (ENOSPC, EDQUOT, EFBIG).
bool is_out_of_space(int error_number);

// "1.2 MiB free on the disk" and, under a file-size limit, "a file may reach 1000 KiB
// (ulimit -f)": what a message about a full disk should say about `path`'s file system.
std::string describe_space(const std::string& path);

// Room kept beyond the end of one file.
class FileRoom {
 public:
  FileRoom() = default;
  // The file at `path`, which must exist; messages call it `name` (default: its path).
  explicit FileRoom(const std::string& path, const std::string& name = "");
  ~FileRoom();
  FileRoom(FileRoom&& other) noexcept;
  FileRoom& operator=(FileRoom&& other) noexcept;
  FileRoom(const FileRoom&) = delete;
  FileRoom& operator=(const FileRoom&) = delete;

  // Makes sure that `bytes` can be written past the file's present end: throws
  // OutOfSpaceError (clean) naming the file, `what` needs the room, and the space left.
  // Reserves twice as much when it can, so that a run reserves about once a frame.
  void keep(std::uint64_t bytes, const std::string& what);
  // Gives back the blocks reserved beyond the end (the file keeps its contents).
  void release();
  const std::string& path() const { return path_; }

 private:
  std::uint64_t size() const;
  bool allocate(std::uint64_t from, std::uint64_t bytes);  // false: no room

  std::string path_, name_;
  int fd_ = -1;
  std::uint64_t reserved_end_ = 0;       // offset up to which the blocks are this file's
  std::uint64_t size_when_reserved_ = 0;  // the file's length then
};

}  // namespace bsmpm
