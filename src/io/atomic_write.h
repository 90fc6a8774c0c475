// Output files appear whole or not at all: written to a temporary name beside the target, then
// renamed over it (rename is atomic on POSIX), so an interrupted run never leaves half a file.
// Every write is checked: a full disk or a file-size limit is an error naming the file.
#pragma once

#include <string>

#include <opencv2/core.hpp>

namespace movseg {

// Encodes `image` by the path's extension (.png, .jpg, ...). Throws std::runtime_error naming
// the path when it cannot be encoded or written.
void writeImageAtomic(const std::string& path, const cv::Mat& image);

void writeTextAtomic(const std::string& path, const std::string& text);

// Creates the folder `path` and its parents. Throws std::runtime_error "cannot create output
// folder ..." when it cannot (a file in the way, no permission).
void makeOutputFolder(const std::string& path);

// The name of frame `index`'s picture among a run's outputs (masks, synthetic frames): 00000.png,
// 00001.png, ..., more digits from 100000 on.
std::string frameFileName(int index);

// A text file grown line by line under PATH.part and renamed to PATH by close(). It holds whole
// lines only: a line that cannot be written completely is cut off again and append() throws.
class LineFile {
 public:
  // Throws std::runtime_error when PATH.part cannot be created.
  explicit LineFile(std::string path);
  ~LineFile();  // closes the file descriptor; PATH.part stays when close() was not called
  LineFile(const LineFile&) = delete;
  LineFile& operator=(const LineFile&) = delete;

  void append(const std::string& line);  // adds line + '\n'
  void close();                          // renames PATH.part to PATH; throws when it cannot

 private:
  std::string path_;
  int fd_ = -1;
  long long size_ = 0;  // bytes of whole lines written
};

}  // namespace movseg
