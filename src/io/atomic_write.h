// Output files appear whole or not at all: written to a temporary name beside the target, then
// renamed over it (rename is atomic on POSIX), so an interrupted run never leaves half a file.
// Every write is checked: a full disk or a file-size limit is an error naming the file.
// A symlink is followed: the file it points to is replaced, not the link. A target that exists
// and is neither a file nor a folder (a device such as /dev/null, a FIFO) is written in place:
// renaming a file over it would replace the node itself, for everyone who uses it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace movseg {

// Encodes `image` by the path's extension (.png, .jpg, ...). Throws std::runtime_error naming
// the path when it cannot be encoded or written.
void writeImageAtomic(const std::string& path, const cv::Mat& image);

void writeTextAtomic(const std::string& path, const std::string& text);

// Throws the std::runtime_error "cannot write 'PATH': ..." that writing PATH would end with (a
// folder in its place, a parent that is not a writable folder), for checking an output before
// the work that makes it. Creates and removes PATH's temporary file to find out.
void checkOutputFile(const std::string& path);

// Creates the folder `path` and its parents. Throws std::runtime_error "cannot create output
// folder ..." when it cannot (a file in the way, no permission).
void makeOutputFolder(const std::string& path);

// A folder's path, absolute and normal, without a trailing separator: "out/", "./out" and "out"
// are one folder.
std::filesystem::path folderPath(const std::string& path);

// The name of frame `index`'s picture among a run's outputs (masks, synthetic frames): 00000.png,
// 00001.png, ..., more digits from 100000 on.
std::string frameFileName(int index);

// What marks a temporary name (temporaryPath()).
constexpr char kTemporaryMark[] = ".part";

// Where a file is written before it is renamed to `path`: beside it, PATH.part, or NAME.part.EXT
// with `keep_extension` (a video writer picks its container by the extension). A name near the
// 255 bytes a file name may have is cut first, so that the temporary one is legal too.
std::string temporaryPath(const std::string& path, bool keep_extension = false);

// Whether `name` (a file name, no folder) is one frameFileName() gives: five or more digits, .png.
bool isFrameFileName(const std::string& name);

// The files of `folder` named as frameFileName() names them, in no particular order; none when
// the folder does not exist. What a run wrote there, to be replaced.
std::vector<std::string> frameFilesIn(const std::string& folder);

// A text file grown line by line under PATH.part and renamed to PATH by close() (a device or FIFO
// is written in place, as above). It holds whole lines only: a line that cannot be written
// completely is cut off again and append() throws.
class LineFile {
 public:
  // Throws std::runtime_error when PATH.part cannot be created or PATH is a folder.
  explicit LineFile(std::string path);
  ~LineFile();  // closes the file descriptor; PATH.part stays when close() was not called
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  void append(const std::string& line);  // adds line + '\n'
  void close();                          // renames PATH.part to PATH; throws when it cannot

 private:
  std::string path_;       // as given, for messages
  std::string target_;     // where the lines go: PATH, or the file a symlink PATH points to
  bool in_place_ = false;  // target_ is a device or FIFO, written directly
  int fd_ = -1;
  long long size_ = 0;  // bytes of whole lines written
};

}  // namespace movseg
