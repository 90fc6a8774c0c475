#include "segment_run.h"


#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "core/frame.h"
#include "movseg/fields.h"
#include "movseg/segmenter.h"
#include "io/atomic_write.h"
#include "io/frame_source.h"
#include "io/overlay.h"
#include "live_window.h"
#include "progress.h"

namespace movseg::cli {
namespace fs = std::filesystem;
namespace {

std::atomic<bool> g_stop{false};
extern "C" void onSignal(int) { g_stop = true; }

// SIGINT / SIGTERM end the run after the current frame; what was written stays complete.
class StopOnSignal {
 public:
  StopOnSignal() {
    g_stop = false;
    previous_int_ = std::signal(SIGINT, onSignal);
    previous_term_ = std::signal(SIGTERM, onSignal);
  }
  ~StopOnSignal() {
    std::signal(SIGINT, previous_int_);
    std::signal(SIGTERM, previous_term_);
  }

 private:
  void (*previous_int_)(int);
  void (*previous_term_)(int);
};

void makeFolder(const std::string& path) {
  std::error_code error;
  fs::create_directories(path, error);
  if (error || !fs::is_directory(path)) {
    throw std::runtime_error("cannot create output folder '" + path + "'" +
                             (error ? ": " + error.message() : ""));
  }
}

std::string frameName(int index) {
  char name[32];
  std::snprintf(name, sizeof name, "%05d.png", index);
  return name;
}

// A field's value as JSON; a camera model as its three rows.
struct ToJson {
  nlohmann::json operator()(const cv::Matx33d& m) const {
    return {{m(0, 0), m(0, 1), m(0, 2)}, {m(1, 0), m(1, 1), m(1, 2)}, {m(2, 0), m(2, 1), m(2, 2)}};
  }
  template <typename T>
  nlohmann::json operator()(const T& value) const {
    return value;
  }
};

// One line of --stats: the frame index and every field of diagnostics.def, by its name.
nlohmann::json statsLine(int index, const Diagnostics& d) {
  nlohmann::json line{{"frame", index}};
  for (const FieldInfo& field : diagnosticFields()) {
    line[field.name] = std::visit(ToJson{}, diagnosticValue(d, field.name));
  }
  return line;
}

// JSON Lines written to FILE.part and renamed to FILE when the run ends (also on a signal).
class StatsWriter {
 public:
  explicit StatsWriter(std::string path) : path_(std::move(path)) {
    if (path_.empty()) return;
    out_.open(path_ + ".part", std::ios::trunc);
    if (!out_) throw std::runtime_error("cannot write stats file '" + path_ + "'");
  }
  void write(const nlohmann::json& line) {
    if (path_.empty()) return;
    out_ << line.dump() << '\n';
  }
  void close() {
    if (path_.empty()) return;
    out_.close();
    std::error_code error;
    fs::rename(path_ + ".part", path_, error);
    if (error) throw std::runtime_error("cannot write stats file '" + path_ + "'");
  }

 private:
  std::string path_;
  std::ofstream out_;
};

bool isVideoPath(const std::string& path) {
  const std::string ext = fs::path(path).extension().string();
  return ext == ".mp4" || ext == ".avi" || ext == ".mkv" || ext == ".mov";
}

// Overlay frames as PNGs in a folder, or as one video written to a temporary name and renamed
// when complete.
class OverlayWriter {
 public:
  explicit OverlayWriter(std::string target) : target_(std::move(target)) {
    if (target_.empty()) return;
    if (isVideoPath(target_)) {
      const fs::path p(target_);
      temporary_ = (p.parent_path() / (p.stem().string() + ".part" + p.extension().string())).string();
    } else {
      makeFolder(target_);
    }
  }
  void write(int index, const cv::Mat& picture) {
    if (target_.empty()) return;
    if (temporary_.empty()) {
      writeImageAtomic((fs::path(target_) / frameName(index)).string(), picture);
      return;
    }
    if (!video_.isOpened()) {
      size_ = picture.size();
      const int fourcc = fs::path(target_).extension() == ".avi"
                             ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
                             : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
      if (!video_.open(temporary_, cv::CAP_FFMPEG, fourcc, 25.0, size_)) {
        throw std::runtime_error("cannot write overlay video '" + target_ + "'");
      }
    }
    if (picture.size() == size_) {
      video_.write(picture);
    } else {
      cv::Mat resized;
      cv::resize(picture, resized, size_);
      video_.write(resized);
    }
  }
  void close() {
    if (!video_.isOpened()) return;
    video_.release();
    std::error_code error;
    fs::rename(temporary_, target_, error);
    if (error) throw std::runtime_error("cannot write overlay video '" + target_ + "'");
  }

 private:
  std::string target_, temporary_;
  cv::VideoWriter video_;
  cv::Size size_;
};

std::string hudLine(int index, const Diagnostics& d) {
  const double ms = d.total_ms;
  char hud[64];
  std::snprintf(hud, sizeof hud, "frame %d  %.0f fps", index, ms > 0 ? 1000.0 / ms : 0.0);
  return hud;
}

void writeDebugPictures(const std::string& folder, int index, const Result& result) {
  for (const auto& [name, picture] : result.debug) {
    if (picture.empty()) continue;
    const fs::path dir = fs::path(folder) / name;
    makeFolder(dir.string());
    writeImageAtomic((dir / frameName(index)).string(), picture);
  }
}

}  // namespace

SegmentSummary runSegmentation(const SegmentOptions& options) {
  LiveWindow window(options.show);
  Params params = options.params;
  params.debug_images = params.debug_images || options.debug;
  Segmenter segmenter(params);
  std::unique_ptr<FrameSource> source = FrameSource::open(options.input);
  if (!options.output_dir.empty()) makeFolder(options.output_dir);
  const std::string debug_dir = (fs::path(options.output_dir) / "debug").string();
  StatsWriter stats(options.stats_file);
  OverlayWriter overlay(options.overlay);
  StopOnSignal stop_on_signal;

  SegmentSummary summary;
  int total = source->frameCount();
  if (options.max_frames >= 0 && (total < 0 || total > options.max_frames)) total = options.max_frames;
  Progress progress("segment", total, options.quiet);
  const auto start = std::chrono::steady_clock::now();
  cv::Mat frame;
  while (options.max_frames < 0 || summary.frames < options.max_frames) {
    if (g_stop) {
      summary.interrupted = true;
      break;
    }
    if (!source->read(&frame)) {
      summary.stream_ended = source->frameCount() < 0;
      break;
    }
    const int index = summary.frames;
    Result result;
    try {
      result = segmenter.process(resizedTo(frame, options.resize));
    } catch (const std::invalid_argument& e) {
      throw std::runtime_error(source->describe() + ": " + e.what());
    }
    if (result.mask.size() != frame.size()) {
      cv::resize(result.mask, result.mask, frame.size(), 0, 0, cv::INTER_NEAREST);
    }
    summary.frame_ms.add(result.diagnostics.total_ms);
    summary.resets += result.diagnostics.reset;
    summary.motion_fallbacks += result.diagnostics.motion_fallback;
    if (!options.output_dir.empty()) {
      writeImageAtomic((fs::path(options.output_dir) / frameName(index)).string(), result.mask);
      if (options.debug) writeDebugPictures(debug_dir, index, result);
    }
    stats.write(statsLine(index, result.diagnostics));
    bool viewer_stopped = false;
    if (!options.overlay.empty() || options.show) {
      const cv::Mat picture = drawOverlay(frame, result, hudLine(index, result.diagnostics));
      overlay.write(index, picture);
      viewer_stopped = !window.show(picture);
    }
    ++summary.frames;
    progress.update(summary.frames);
    if (viewer_stopped) break;
  }
  progress.finish();
  summary.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  stats.close();
  overlay.close();
  if (summary.frames == 0 && !summary.interrupted) {
    throw std::runtime_error("no frames in '" + options.input + "'" +
                             (summary.stream_ended ? " (the stream ended or stalled)" : ""));
  }
  return summary;
}

std::string describeSummary(const SegmentSummary& summary) {
  const double ms = summary.frame_ms.median();
  char line[160];
  std::snprintf(line, sizeof line, "%d frames in %.2f s (%.1f fps overall, median %.2f ms/frame)",
                summary.frames, summary.seconds,
                summary.seconds > 0 ? summary.frames / summary.seconds : 0.0, ms);
  std::string text = line;
  if (summary.resets > 0) text += ", " + std::to_string(summary.resets) + " size resets";
  if (summary.motion_fallbacks > 0) {
    text += ", " + std::to_string(summary.motion_fallbacks) + " alignment fallbacks";
  }
  return text;
}

}  // namespace movseg::cli
