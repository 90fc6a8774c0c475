// Per-stage and whole-pipeline timings on synthetic frame pairs at 320x240 and 640x480.
//   build/bench/movseg_bench [--benchmark_filter=...]
// Each stage runs on the output of the previous ones for the same pair, exactly as in the
// paper's pipeline (src/pipelines/paper.cc), so the stage times add up to the pipeline's.
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>

#include "classify/classify.h"
#include "core/frame.h"
#include "cut/geodesic.h"
#include "cut/graph_cut.h"
#include "motion/camera_tracker.h"
#include "motion/model.h"
#include "movseg/segmenter.h"
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
    const FeatureClasses classes = classifyFeatures(
        difference, image.seg_bgr, points, step.staticPoints(image.seg_scale), params);
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
    benchmark::DoNotOptimize(compensatedDifference(in.prev->image.seg_smooth, cur.seg_smooth, model));
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

// range(2): cut band (0 = whole image), range(3): 0 OpenCV's max-flow, 1 Boost's.
void BM_GraphCut(benchmark::State& state) {
  StageInputs in(synthPair(state));
  in.params.cut_band = static_cast<int>(state.range(2));
  const auto solver = state.range(3) == 0 ? MaxFlowSolver::kOpenCv : MaxFlowSolver::kBoost;
  int nodes = 0;
  for (auto _ : state) {
    const CutResult cut = geodesicGraphCut(in.cur->image.seg_bgr, in.fg, in.bg, in.params, solver);
    nodes = cut.graph_nodes;
  }
  state.counters["graph_nodes"] = nodes;
}

void BM_Process(benchmark::State& state) {
  const Pair pair = synthPair(state);
  Segmenter segmenter;
  bool odd = false;
  for (auto _ : state) {  // each call is a real pair (alternating direction)
    benchmark::DoNotOptimize(segmenter.process(odd ? pair.prev : pair.cur));
    odd = !odd;
  }
}

void sizes(benchmark::internal::Benchmark* b) {
  b->Args({320, 240})->Args({640, 480})->Unit(benchmark::kMillisecond);
}

void cutVariants(benchmark::internal::Benchmark* b) {
  for (int band : {0, 8}) {
    for (int solver : {0, 1}) b->Args({320, 240, band, solver});
  }
  b->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_Prepare)->Apply(sizes);
BENCHMARK(BM_Motion)->Apply(sizes);
BENCHMARK(BM_Difference)->Apply(sizes);
BENCHMARK(BM_Classify)->Apply(sizes);
BENCHMARK(BM_GeodesicDistances)->Apply(sizes);
BENCHMARK(BM_GraphCut)->Apply(cutVariants);
BENCHMARK(BM_Process)->Apply(sizes);

}  // namespace
}  // namespace movseg

int main(int argc, char** argv) {
  cv::setNumThreads(1);  // single-thread figures, as the CLI runs
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
