// Timings of the paper's stages on synthetic frame pairs at 320x240 and 640x480, of `dense`'s
// edge snap beside the guided filter of OpenCV's ximgproc, of `dense`'s flow beside OpenCV's DIS,
// of every method's whole pipeline on synthetic and DAVIS clips beside OpenCV MOG2 (method
// mog2), and of DAVIS's boundary F of an 854x480 mask pair beside the two whole-frame dilations
// it replaced.
//   build/bench/movseg_bench [--benchmark_filter=...]
// Each paper stage runs on the output of the previous ones for the same pair, exactly as in the
// paper's pipeline (src/pipelines/paper.cc), so the stage times add up to the pipeline's. The
// whole-pipeline figures split a frame's time by stage from Diagnostics and count the minor page
// faults per frame (memory the pipeline hands back and takes again).
// DAVIS clips are read from $MOVSEG_DATA/davis2016 (default ../shared/data/davis2016 beside the
// source tree) and left out when absent.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/ximgproc/edge_filter.hpp>
#include <string>
#include <vector>

#include "classify/classify.h"
#include "core/frame.h"
#include "cut/geodesic.h"
#include "cut/graph_cut.h"
#include "eval/metrics.h"
#include "flow/dense_flow.h"
#include "io/frame_source.h"
#include "motion/camera_tracker.h"
#include "motion/model.h"
#include "movseg/fields.h"
#include "movseg/segmenter.h"
#include "opencv_dense_flow.h"
#include "refine/edge_snap.h"
#include "synth/synth.h"

namespace movseg {
namespace {

struct Pair {
  cv::Mat prev, cur;
};

Pair synthPair(const benchmark::State& state) {
  SynthOptions options;
  options.size = cv::Size(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  options.frames = 12;
  const SynthSequence sequence(options);
  return {sequence.frame(10).frame, sequence.frame(11).frame};
}

// Everything a stage needs from the stages before it, computed as the paper's pipeline does.
struct StageInputs {
  Params params;
  CameraTracker tracker{params};
  CameraTracker::Step step;
  const TrackedFrame* prev = nullptr;
  const TrackedFrame* cur = nullptr;
  cv::Mat difference;
  std::vector<cv::Point2f> points;  // the current frame's features, segmentation scale
  std::vector<cv::Point> fg, bg;

  explicit StageInputs(const Pair& pair) {
    tracker.advance(pair.prev.clone());
    step = tracker.advance(pair.cur.clone());
    prev = step.previous.get();
    cur = step.current.get();
    const PreparedFrame& image = cur->image;
    difference = compensatedDifference(prev->image.seg_smooth, image.seg_smooth,
                                       rescaleModel(step.model, image.seg_scale));
    const auto s = static_cast<float>(image.seg_scale / image.align_scale);
    for (const cv::Point2f& p : cur->alignment.features) points.push_back(p * s);
    const FeatureClasses classes = classifyFeatures(difference, image.seg_bgr, points,
                                                    step.staticPoints(image.seg_scale), params);
    for (size_t i = 0; i < points.size(); ++i) {
      if (classes.labels[i] == FeatureLabel::kForeground) fg.push_back(points[i]);
      if (classes.labels[i] == FeatureLabel::kBackground) bg.push_back(points[i]);
    }
  }
};

void BM_Prepare(benchmark::State& state) {
  const Pair pair = synthPair(state);
  const Params params;
  for (auto _ : state) {
    const PreparedFrame frame = prepareFrame(pair.cur, params);
    benchmark::DoNotOptimize(prepareAlignment(frame.small_grey, params));
  }
}

void BM_Motion(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  for (auto _ : state) {
    benchmark::DoNotOptimize(estimateCameraMotion(in.prev->alignment, in.cur->alignment,
                                                  in.step.motion.model, in.params, 0));
  }
}

void BM_Difference(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  const PreparedFrame& cur = in.cur->image;
  const cv::Matx33d model = rescaleModel(in.step.model, cur.seg_scale);
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        compensatedDifference(in.prev->image.seg_smooth, cur.seg_smooth, model));
  }
}

// §3.2: eq. (3) at the features and the GMM refinement.
void BM_Classify(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  const PreparedFrame& cur = in.cur->image;
  for (auto _ : state) {
    benchmark::DoNotOptimize(classifyFeatures(in.difference, cur.seg_bgr, in.points,
                                              in.step.staticPoints(cur.seg_scale), in.params));
  }
}

void BM_GeodesicDistances(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  cv::Mat colour;
  in.cur->image.seg_bgr.convertTo(colour, CV_32FC3, 1.0 / 255.0);
  for (auto _ : state) {
    const GeodesicGrid grid(colour, in.params.geodesic_gamma);
    benchmark::DoNotOptimize(grid.distanceFrom(in.fg, 1));
    benchmark::DoNotOptimize(grid.distanceFrom(in.bg, 1));
  }
}

// range(2): cut band (0 = whole image), range(3): 0 OpenCV's max-flow, 1 Boost's, 2 the grid's.
void BM_GraphCut(benchmark::State& state) {
  StageInputs in(synthPair(state));
  in.params.cut_band = static_cast<int>(state.range(2));
  const MaxFlowSolver solvers[] = {MaxFlowSolver::kOpenCv, MaxFlowSolver::kBoost,
                                   MaxFlowSolver::kGrid};
  const MaxFlowSolver solver = solvers[state.range(3)];
  int nodes = 0;
  for (auto _ : state) {
    const CutResult cut = geodesicGraphCut(in.cur->image.seg_bgr, in.fg, in.bg, in.params, solver);
    nodes = cut.graph_nodes;
  }
  state.counters["graph_nodes"] = nodes;
}

// `dense`'s last step (src/refine/edge_snap.h) against the library's guided filter it computes
// (whole image, then the half level): argument 0 = EdgeSnap, 1 = cv::ximgproc::guidedFilter,
// 2 = EdgeSnap with its result at 8/3 the size (a DAVIS frame's 854 px against the working 320),
// placed by the edges of the frame scaled up (the scale-up of the mask, which upscaledMask did
// before, included). The mask is the synthetic frame's true one moved a pixel, as the cut's
// blocks leave it.
void BM_EdgeSnap(benchmark::State& state) {
  SynthOptions options;
  options.frames = 12;
  const SynthFrame frame = SynthSequence(options).frame(11);
  cv::Mat mask;
  cv::warpAffine(frame.mask, mask, cv::Matx23d(1, 0, 1, 0, 1, 1), frame.mask.size(),
                 cv::INTER_NEAREST);
  const int radius = Params().edge_snap;
  EdgeSnap snap;
  cv::Mat grey, input_grey, label, filtered;
  cv::cvtColor(frame.frame, grey, cv::COLOR_BGR2GRAY);
  cv::resize(grey, input_grey, {}, 8.0 / 3, 8.0 / 3, cv::INTER_LINEAR);
  for (auto _ : state) {
    if (state.range(0) != 1) {
      benchmark::DoNotOptimize(
          snap.snap(mask, grey, radius, state.range(0) == 2 ? input_grey : cv::Mat()));
    } else {
      mask.convertTo(label, CV_32F, 1.0 / 255);
      cv::ximgproc::guidedFilter(grey, label, filtered, radius, EdgeSnap::kRegulariser);
      benchmark::DoNotOptimize(filtered > 0.5);
    }
  }
}

// Frames played forwards then backwards, so that every call is a real pair, the wrap included.
struct Clip {
  std::string name;
  std::vector<cv::Mat> frames;
  const cv::Mat& frame(size_t call) const {
    const size_t period = 2 * frames.size() - 2;
    const size_t i = call % period;
    return frames[i < frames.size() ? i : period - i];
  }
};

Clip synthClip(cv::Size size) {
  SynthOptions options;
  options.size = size;
  options.frames = 12;
  const SynthSequence sequence(options);
  Clip clip{"synth/" + std::to_string(size.width) + "x" + std::to_string(size.height), {}};
  for (int i = 0; i < options.frames; ++i) clip.frames.push_back(sequence.frame(i).frame);
  return clip;
}

std::string davisRoot() {
  const char* data = std::getenv("MOVSEG_DATA");
  return (data != nullptr ? std::string(data)
                          : std::string(MOVSEG_SOURCE_DIR) + "/../shared/data") +
         "/davis2016";
}

// The first 12 frames of a DAVIS sequence, resized to `size` (empty: as stored); no frames when
// the data is absent.
Clip davisClip(const std::string& sequence, cv::Size size) {
  Clip clip{"davis-" + sequence + "/" +
                (size.empty() ? "native"
                              : std::to_string(size.width) + "x" + std::to_string(size.height)),
            {}};
  const std::string folder = davisRoot() + "/" + sequence + "/frames";
  if (!std::filesystem::is_directory(folder)) return clip;
  std::vector<std::string> files = listImages(folder);
  files.resize(std::min<size_t>(files.size(), 12));
  for (const std::string& file : files) {
    cv::Mat frame = cv::imread(file);
    if (frame.empty()) return {};
    if (!size.empty()) cv::resize(frame, frame, size, 0, 0, cv::INTER_AREA);
    clip.frames.push_back(frame);
  }
  return clip;
}

long minorFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

void processClip(benchmark::State& state, const Clip& clip, const std::string& method) {
  Params params;
  setParam(&params, "method", method);
  Segmenter segmenter(params);
  for (size_t i = 0; i < clip.frames.size(); ++i) segmenter.process(clip.frame(i));  // warm up
  Diagnostics sum;
  size_t call = 0;
  const long faults = minorFaults();
  for (auto _ : state) {
    const Diagnostics d = segmenter.process(clip.frame(call++)).diagnostics;
    sum.prepare_ms += d.prepare_ms;
    sum.motion_ms += d.motion_ms;
    sum.classify_ms += d.classify_ms;
    sum.cut_ms += d.cut_ms;
  }
  const auto n = static_cast<double>(std::max<size_t>(call, 1));
  state.counters["faults"] = static_cast<double>(minorFaults() - faults) / n;
  state.counters["prepare_ms"] = sum.prepare_ms / n;
  state.counters["motion_ms"] = sum.motion_ms / n;
  state.counters["classify_ms"] = sum.classify_ms / n;
  state.counters["cut_ms"] = sum.cut_ms / n;
}

// The flow of a clip's pairs as `dense` computes it, one pair an iteration: from each frame to
// the previous one, from the previous pair's flow (DenseFlow), by movseg's DisFlow or, as
// before it, by OpenCV's cv::DISOpticalFlow at the same settings (the same flows).
template <class Flow>
void denseFlowClip(benchmark::State& state, const Clip& clip) {
  Clip grey{clip.name, {}};
  for (const cv::Mat& frame : clip.frames) {
    grey.frames.emplace_back();
    cv::cvtColor(frame, grey.frames.back(), cv::COLOR_BGR2GRAY);
  }
  Flow flow(Params().flow_finest_scale);
  cv::Mat flows[2];  // two in flight, as the pipeline keeps them
  size_t call = 0;
  for (; call < grey.frames.size(); ++call) flow.next(grey.frame(call), &flows[call % 2]);
  for (auto _ : state) {
    flow.next(grey.frame(call), &flows[call % 2]);
    ++call;
  }
}

// Decoding a frame file as the CLI reads it (decodeImage: libjpeg-turbo directly, its warnings
// caught) beside cv::imread, on DAVIS dog's first 12 JPEG frames (854x480): the reading thread
// of `segment --threads 2` decodes, and its time bounds one stream's speed-up.
void decodeFrames(benchmark::State& state, const std::vector<std::string>& files, bool ours) {
  size_t i = 0;
  for (auto _ : state) {
    const std::string& file = files[i++ % files.size()];
    cv::Mat frame =
        ours ? decodeImage(file, cv::IMREAD_UNCHANGED) : cv::imread(file, cv::IMREAD_UNCHANGED);
    benchmark::DoNotOptimize(frame.data);
  }
}

// BM_Process/<clip>/<method> for every method on each clip that could be read,
// BM_DenseFlow/<clip>/<implementation> on those at 320x240, and BM_DecodeFrame/davis-dog/<reader>.
void registerPipelines() {
  std::vector<Clip> clips = {synthClip({320, 240}), synthClip({640, 480})};
  for (const cv::Size size : {cv::Size(320, 240), cv::Size()}) {
    Clip clip = davisClip("dog", size);
    if (!clip.frames.empty()) clips.push_back(std::move(clip));
  }
  for (const Clip& clip : clips) {
    if (clip.frames.front().size() != cv::Size(320, 240)) continue;
    benchmark::RegisterBenchmark(("BM_DenseFlow/" + clip.name + "/opencv").c_str(),
                                 [clip](benchmark::State& state) {
                                   denseFlowClip<OpenCvDenseFlow>(state, clip);
                                 })
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_DenseFlow/" + clip.name + "/movseg").c_str(),
                                 [clip](benchmark::State& state) {
                                   denseFlowClip<DenseFlow>(state, clip);
                                 })
        ->Unit(benchmark::kMillisecond);
  }
  const std::string dog = davisRoot() + "/dog/frames";
  if (std::filesystem::is_directory(dog)) {
    std::vector<std::string> files = listImages(dog);
    files.resize(std::min<size_t>(files.size(), 12));
    for (const bool ours : {true, false}) {
      benchmark::RegisterBenchmark(
          (std::string("BM_DecodeFrame/davis-dog/") + (ours ? "movseg" : "imread")).c_str(),
          [files, ours](benchmark::State& state) { decodeFrames(state, files, ours); })
          ->Unit(benchmark::kMillisecond);
    }
  }
  for (const Clip& clip : clips) {
    for (const std::string& method : enumNames<Method>()) {
      benchmark::RegisterBenchmark(
          ("BM_Process/" + clip.name + "/" + method).c_str(),
          [clip, method](benchmark::State& state) { processClip(state, clip, method); })
          ->Unit(benchmark::kMillisecond);
    }
  }
}

// A DAVIS-sized pair of masks: discs, the prediction's moved by a few pixels and speckled.
std::pair<cv::Mat, cv::Mat> discMasks() {
  cv::RNG rng(3);
  cv::Mat pred = cv::Mat::zeros(480, 854, CV_8U), truth = pred.clone();
  for (int i = 0; i < 4; ++i) {
    const cv::Point centre(rng.uniform(100, 750), rng.uniform(100, 380));
    const int radius = rng.uniform(20, 100);
    cv::circle(truth, centre, radius, 255, cv::FILLED);
    cv::circle(pred, centre + cv::Point(rng.uniform(-6, 7), rng.uniform(-6, 7)), radius, 255,
               cv::FILLED);
  }
  for (int i = 0; i < 2000; ++i) pred.at<uchar>(rng.uniform(0, 480), rng.uniform(0, 854)) ^= 255;
  return {pred, truth};
}

// DAVIS's F of a pair of 854x480 masks (eval/metrics.h), beside what computing it cost before
// its boundary maps were even made: two whole-frame dilations by cv::dilate with a 17x17 disk
// (OpenCV's ellipse, as costly as DAVIS's disk of 8 pixels).
void BM_BoundaryF(benchmark::State& state) {
  const auto [pred, truth] = discMasks();
  for (auto _ : state) benchmark::DoNotOptimize(boundaryF(pred, truth));
}

void BM_BoundaryDilation(benchmark::State& state) {
  const auto [pred, truth] = discMasks();
  const cv::Mat disk = cv::getStructuringElement(cv::MORPH_ELLIPSE, {17, 17});
  cv::Mat pred_near, truth_near;
  for (auto _ : state) {
    cv::dilate(pred, pred_near, disk);
    cv::dilate(truth, truth_near, disk);
  }
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({320, 240})->Args({640, 480})->Unit(benchmark::kMillisecond);
}

void cutVariants(benchmark::internal::Benchmark* b) {
  for (int band : {0, 8}) {
    for (int solver : {0, 1, 2}) b->Args({320, 240, band, solver});
  }
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Prepare)->Apply(sizes);
BENCHMARK(BM_Motion)->Apply(sizes);
BENCHMARK(BM_Difference)->Apply(sizes);
BENCHMARK(BM_Classify)->Apply(sizes);
BENCHMARK(BM_GeodesicDistances)->Apply(sizes);
BENCHMARK(BM_GraphCut)->Apply(cutVariants);
BENCHMARK(BM_EdgeSnap)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BoundaryF)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BoundaryDilation)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace movseg

int main(int argc, char** argv) {
  cv::setNumThreads(1);  // single-thread figures, as the CLI runs
  benchmark::Initialize(&argc, argv);
  movseg::registerPipelines();
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
