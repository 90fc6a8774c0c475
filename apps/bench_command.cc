// movseg bench DATA [--methods dense,paper,diff,mog2,mog2-comp] [--size WxH] [--threads N]
//                   [--ignore IMAGE] [--json FILE] [--html FILE] [--<parameter> VALUE ...]
//                   [--set name=value ...]
// Every method on every sequence of DATA: accuracy against the ground truth and speed, in one
// table (the README's tables come from here); with --threads, what threads add to throughput.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <sys/resource.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "commands.h"
#include "concurrent.h"
#include "eval/dataset.h"
#include "html_report.h"
#include "io/atomic_write.h"
#include "io/json_text.h"
#include "movseg/fields.h"
#include "params_options.h"
#include "progress.h"
#include "segment_run.h"

namespace movseg::cli {
namespace {

namespace fs = std::filesystem;

struct BenchOptions {
  std::string data;
  std::vector<std::string> methods = enumNames<Method>();
  std::string size;  // "WxH" or empty (native)
  cv::Size resize;   // size, parsed; empty for native
  std::string json_file;
  std::string html_file;
  std::string ignore;  // segment's --ignore, for every run
  Params params;
  int threads = 1;  // runs at a time
};

// Timed in every run beside the methods asked for: OpenCV's MOG2, the speed users compare with.
constexpr const char* kReference = "mog2";

struct BenchRow {
  std::string sequence, method;
  ScoreSummary score;
  double ms_per_frame = 0;      // median process() wall time
  double faults_per_frame = 0;  // minor page faults of the whole run (reads, writes included)
  double vs_reference = 0;      // ms_per_frame over kReference's on the same sequence(s)
  ReportRun report;             // with --html only
};

// The calling thread's: runs at once each count their own.
long minorFaults() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_minflt;
}

// --size: frames as large as a video can hold; larger is a typo.
cv::Size benchSize(const std::string& text) {
  constexpr int kMaxSide = 8192;
  const cv::Size size = parseSize("--size", text);
  if (size.width < 1 || size.height < 1 || size.width > kMaxSide || size.height > kMaxSide) {
    throw UsageError("--size must be within 1x1 .. 8192x8192 (got '" + text + "')");
  }
  return size;
}

// The CPU, for the table's header: benchmarks only compare on the same machine.
std::string cpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  }
  return "unknown CPU";
}

// The folder the runs write their masks in, removed however the bench ends (a failed sequence,
// a signal): what stays in /tmp after a bench is only its report.
class ScratchFolder {
 public:
  ScratchFolder() : path_(temporaryFolder() / ("movseg-bench-" + pid())) {}
  ~ScratchFolder() {
    std::error_code error;
    fs::remove_all(path_, error);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;
  std::string path() const { return path_.string(); }

 private:
  static std::string pid() { return std::to_string(::getpid()); }
  fs::path path_;
};

// Thrown out of the runs once SIGINT or SIGTERM stopped one (StopOnSignal): the bench ends
// without a table, which would compare cut-short runs with whole ones.
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted") {}
};

// runSegmentation, ended by Interrupted when a signal stopped it or came before it began.
SegmentSummary runUnlessInterrupted(const SegmentOptions& segment) {
  if (StopOnSignal::stopped()) throw Interrupted();
  const SegmentSummary summary = runSegmentation(segment);
  if (summary.interrupted) throw Interrupted();
  return summary;
}

// A run of `method` on `sequence`, its masks written under `scratch`.
SegmentOptions runOptions(const GtSequence& sequence, const std::string& method,
                          const BenchOptions& options, const std::string& scratch) {
  SegmentOptions segment;
  segment.input = sequence.frames_dir;
  segment.output_dir = (fs::path(scratch) / method / sequence.name).string();
  segment.params = options.params;
  setParam(&segment.params, "method", method);
  segment.quiet = true;
  segment.resize = options.resize;
  segment.ignore = options.ignore;
  return segment;
}

BenchRow benchOne(const GtSequence& sequence, const std::string& method, const BenchOptions& options,
                  const std::string& scratch) {
  const SegmentOptions segment = runOptions(sequence, method, options, scratch);
  const long faults = minorFaults();
  const SegmentSummary summary = runUnlessInterrupted(segment);
  const double faults_per_frame =
      static_cast<double>(minorFaults() - faults) / std::max(summary.frames, 1);
  const SequenceScore score = scoreSequence(sequence, segment.output_dir);
  BenchRow row{sequence.name, method, summarize(score), summary.frame_ms.median(),
               faults_per_frame, 0, {}};
  if (!options.html_file.empty()) {
    row.report = reportRun(sequence, score, segment.output_dir, method, row.ms_per_frame);
  }
  fs::remove_all(segment.output_dir);
  return row;
}

std::string formatRows(const std::vector<BenchRow>& rows) {
  std::string text;
  char line[220];
  std::snprintf(line, sizeof line, "%-22s %-10s %6s %6s %8s %9s %8s %9s %8s\n", "sequence",
                "method", "J", "F", "error %", "ms/frame", "fps", "x mog2", "faults");
  text += line;
  for (const BenchRow& r : rows) {
    std::snprintf(line, sizeof line, "%-22s %-10s %6.3f %6.3f %8.2f %9.2f %8.1f %9.2f %8.1f\n",
                  r.sequence.c_str(), r.method.c_str(), r.score.j, r.score.f, r.score.error_rate,
                  r.ms_per_frame, r.ms_per_frame > 0 ? 1000.0 / r.ms_per_frame : 0.0,
                  r.vs_reference, r.faults_per_frame);
    text += line;
  }
  return text;
}

// Each row's time over the reference's on the same sequence ("MEAN" rows: on the mean).
void compareWithReference(std::vector<BenchRow>* rows) {
  for (BenchRow& row : *rows) {
    for (const BenchRow& reference : *rows) {
      if (reference.method == kReference && reference.sequence == row.sequence &&
          reference.ms_per_frame > 0) {
        row.vs_reference = row.ms_per_frame / reference.ms_per_frame;
      }
    }
  }
}

// One mean row per method, each sequence weighing the same.
std::vector<BenchRow> meanRows(const std::vector<BenchRow>& rows,
                               const std::vector<std::string>& methods) {
  std::vector<BenchRow> means;
  for (const std::string& method : methods) {
    std::vector<ScoreSummary> scores;
    double ms = 0, faults = 0;
    for (const BenchRow& r : rows) {
      if (r.method != method) continue;
      scores.push_back(r.score);
      ms += r.ms_per_frame;
      faults += r.faults_per_frame;
    }
    const auto n = static_cast<double>(std::max<size_t>(scores.size(), 1));
    means.push_back({"MEAN", method, meanOverSequences(scores, "MEAN"), ms / n, faults / n, 0, {}});
  }
  return means;
}

nlohmann::json rowsJson(const std::vector<BenchRow>& rows) {
  nlohmann::json out = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    out.push_back({{"sequence", r.sequence}, {"method", r.method}, {"frames", r.score.frames},
                   {"J", r.score.j}, {"J_recall", r.score.j_recall}, {"F", r.score.f},
                   {"error_rate", r.score.error_rate}, {"ms_per_frame", r.ms_per_frame},
                   {"x_mog2", r.vs_reference}, {"faults_per_frame", r.faults_per_frame}});
  }
  return out;
}

// What threads add: fps of whole runs of one method over every sequence (frames read,
// segmented, masks written), one stream on one thread and on two, and several streams at once.
struct Throughput {
  std::string method;
  int streams = 0;  // at once
  double one_thread = 0, two_threads = 0, at_once = 0;
};

// Frames per second of `method` over every sequence, `streams` at a time, each stream on
// `stream_threads`.
double framesPerSecond(const std::vector<GtSequence>& sequences, const std::string& method,
                       const BenchOptions& options, const std::string& scratch, int streams,
                       int stream_threads) {
  std::atomic<int> frames{0};
  const auto start = std::chrono::steady_clock::now();
  runConcurrently(sequences.size(), streams, [&](size_t i) {
    SegmentOptions segment = runOptions(sequences[i], method, options, scratch);
    segment.threads = stream_threads;
    frames += runUnlessInterrupted(segment).frames;
  });
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  fs::remove_all(fs::path(scratch) / method);  // untimed, and the next pass writes there again
  return frames / seconds;
}

// Each configuration's best of kThroughputRounds, the rounds interleaved: on a shared machine
// another job's burst slows one round of each configuration rather than one configuration.
constexpr int kThroughputRounds = 3;

Throughput measureThroughput(const std::vector<GtSequence>& sequences, const std::string& method,
                             const BenchOptions& options, const std::string& scratch) {
  Throughput t;
  t.method = method;
  t.streams = static_cast<int>(std::min<size_t>(options.threads, sequences.size()));
  const auto fps = [&](int streams, int stream_threads) {
    return framesPerSecond(sequences, method, options, scratch, streams, stream_threads);
  };
  for (int round = 0; round < kThroughputRounds; ++round) {
    t.one_thread = std::max(t.one_thread, fps(1, 1));
    t.two_threads = std::max(t.two_threads, fps(1, 2));
    t.at_once = std::max(t.at_once, fps(t.streams, 1));
  }
  return t;
}

std::string formatThroughput(const Throughput& t) {
  char text[600];
  std::snprintf(text, sizeof text,
                "Throughput of %s, whole runs over every sequence (frames read, segmented, masks "
                "written), frames per second, best of %d rounds:\n"
                "  one stream on 1 thread   %8.1f\n"
                "  one stream on 2 threads  %8.1f  %.2fx 1 thread (target 1.6x)\n"
                "  %d streams at once        %8.1f  %.2fx one at a time (target 1.8x for 2)\n",
                t.method.c_str(), kThroughputRounds, t.one_thread, t.two_threads,
                t.two_threads / t.one_thread, t.streams, t.at_once, t.at_once / t.one_thread);
  return text;
}

// Every method on every sequence, options.threads runs at a time, in the table's order.
std::vector<BenchRow> benchAll(const std::vector<GtSequence>& sequences,
                               const std::vector<std::string>& methods, const BenchOptions& options,
                               const std::string& scratch) {
  std::vector<BenchRow> rows(sequences.size() * methods.size());
  Progress progress("bench", static_cast<int>(rows.size()), false, "runs");
  std::mutex progress_mutex;
  int done = 0;
  try {
    runConcurrently(rows.size(), options.threads, [&](size_t i) {
      rows[i] =
          benchOne(sequences[i / methods.size()], methods[i % methods.size()], options, scratch);
      const std::lock_guard<std::mutex> lock(progress_mutex);
      progress.update(++done);
    });
  } catch (...) {
    progress.finish();  // the error's line starts a line of its own
    throw;
  }
  progress.finish();
  return rows;
}

// A method named twice would be benched twice into one scratch folder.
void refuseRepeatedMethods(const std::vector<std::string>& methods) {
  for (size_t i = 0; i < methods.size(); ++i) {
    if (std::find(methods.begin(), methods.begin() + static_cast<long>(i), methods[i]) !=
        methods.begin() + static_cast<long>(i)) {
      throw UsageError("--methods: '" + methods[i] + "' is named twice");
    }
  }
}

void runBench(const BenchOptions& options) {
  // One for the whole bench, from its start: a signal before or between runs is not lost.
  const StopOnSignal stop_on_signal;
  options.params.check();
  const std::vector<GtSequence> sequences = loadGroundTruth(options.data, GtFormat::kAuto);
  // What cannot be written fails now, not after the whole bench; none inside the dataset or the
  // sequences' folders, also where they are links out of it.
  std::vector<std::string> inputs = sequenceFolders(sequences, "");
  inputs.insert(inputs.end(), {options.data, options.ignore});
  checkReportPaths({{"--json", options.json_file}, {"--html", options.html_file}}, inputs);
  requireFramesToScore(sequences);
  for (const GtSequence& s : sequences) {
    if (s.frames_dir.empty()) {
      throw std::runtime_error("sequence '" + s.name + "' has no frames folder to segment");
    }
  }
  std::vector<std::string> methods = options.methods;
  if (std::find(methods.begin(), methods.end(), kReference) == methods.end()) {
    methods.push_back(kReference);
  }
  std::vector<BenchRow> rows;
  std::optional<Throughput> throughput;
  {
    const ScratchFolder scratch;
    try {
      rows = benchAll(sequences, methods, options, scratch.path());
      if (options.threads > 1) {
        throughput = measureThroughput(sequences, methods.front(), options, scratch.path());
      }
    } catch (const Interrupted&) {
      std::cerr << "movseg: interrupted; no table written\n";
      throw CLI::RuntimeError(kExitInterrupted);
    }
  }
  std::vector<BenchRow> means = meanRows(rows, methods);
  compareWithReference(&rows);
  compareWithReference(&means);
  const std::string threads =
      options.threads == 1 ? "one thread"
                           : std::to_string(options.threads) + " runs at a time, one thread each";
  const std::string setting =
      "movseg bench on " + cpuModel() + ", " + threads +
      (options.size.empty() ? ", native size" : ", frames resized to " + options.size) +
      (options.ignore.empty() ? "" : ", ignoring " + options.ignore);
  std::cout << setting << "\n"
            << formatRows(rows) << formatRows(means).substr(formatRows({}).size())
            << "J, F, error: means over frames after the first of each sequence (it has no "
               "previous frame); MEAN rows: each sequence weighs the same; ms/frame: median "
               "per-frame time of the method (MEAN: mean of the medians); x mog2: over OpenCV "
               "MOG2's, timed in the same run; faults: minor page faults per frame of the whole "
               "run (reading and writing included).\n"
            << (throughput ? formatThroughput(*throughput) : "");
  if (!options.json_file.empty()) {
    // The settings every method ran with (each its own `method`), as a run's manifest has them.
    nlohmann::json settings = paramSettings(options.params, {"method"});
    if (!options.ignore.empty()) settings["ignore"] = options.ignore;
    nlohmann::json report{{"cpu", cpuModel()},         {"size", options.size},
                          {"threads", options.threads}, {"settings", settings},
                          {"rows", rowsJson(rows)},     {"means", rowsJson(means)}};
    if (throughput) {
      report["throughput"] = {{"method", throughput->method},
                              {"one_thread_fps", throughput->one_thread},
                              {"two_threads_fps", throughput->two_threads},
                              {"streams", throughput->streams},
                              {"streams_at_once_fps", throughput->at_once}};
    }
    writeTextAtomic(options.json_file, jsonText(report, 2) + "\n");
  }
  if (!options.html_file.empty()) {
    std::vector<ReportRun> runs;
    for (const BenchRow& row : rows) runs.push_back(row.report);
    writeHtmlReport(options.html_file, "movseg bench: " + options.data, setting, runs);
  }
}

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Accuracy and speed of every method on every sequence of a dataset");
  cmd->add_option("DATA", options->data,
                  "Dataset folder (<sequence>/frames + <sequence>/masks, or a single sequence)")
      ->required();
  cmd->add_option("--methods", options->methods, "Comma-separated methods")
      ->delimiter(',')
      ->check(CLI::IsMember(enumNames<Method>()));
  cmd->add_option("--size", options->size, "Resize frames to WxH before segmenting");
  cmd->add_option("--threads", options->threads,
                  "Runs at a time, one thread each (the table's accuracy is the same); from 2, "
                  "also the throughput of one stream on 1 and 2 threads and of N streams at once")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--ignore", options->ignore,
                  "An image, white where nothing moves (as segment's), for every sequence")
      ->type_name("IMAGE");
  cmd->add_option("--json", options->json_file, "Write the table as JSON");
  cmd->add_option("--html", options->html_file,
                  "Write a report page: the table, charts of J, each sequence's worst frames");
  addParamsOptions(cmd, &options->params, {"method"});
  cmd->callback([options, cmd] {
    refuseEmptyNames(*cmd, {"--json", "--html", "--ignore"});
    refuseRepeatedMethods(options->methods);
    if (!options->size.empty()) options->resize = benchSize(options->size);
    runBench(*options);
  });
}

}  // namespace movseg::cli
