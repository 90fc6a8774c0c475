// Per-stage and whole-pipeline timings on synthetic frame pairs at 320x240 and 640x480.
//   build/bench/movseg_bench [--benchmark_filter=...]
// Each stage runs on the output of the previous ones for the same pair, exactly as in
// Segmenter::process, so the stage times add up to the pipeline's.
#include <benchmark/benchmark.h>

#include <opencv2/core/utility.hpp>

#include "classify/classify.h"
#include "core/camera_tracker.h"
#include "core/frame.h"
#include "cut/geodesic.h"
#include "cut/graph_cut.h"
#include "motion/compensation.h"
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

// Everything a stage needs from the stages before it.
struct StageInputs {
  Params params;
  PreparedFrame prev, cur;
  MotionEstimate motion;
  cv::Mat difference;
  std::vector<cv::Point> fg, bg;

  explicit StageInputs(const Pair& pair) {
    prev = prepareFrame(pair.prev, params);
    cur = prepareFrame(pair.cur, params);
    motion = estimateCameraMotion(prev, cur, cv::Matx33d::eye(), params, 0);
    const double s = cur.seg_scale / cur.align_scale;
    difference = compensatedDifference(prev.seg_smooth, cur.seg_smooth, rescaleModel(motion.model, s));
    const double lambda = chooseLambda(difference, staticPoints(motion, cur, cur.seg_scale), params);
    std::vector<cv::Point2f> points;
    for (const cv::Point2f& p : cur.features) points.push_back(p * static_cast<float>(s));
    const std::vector<FeatureLabel> labels = classifyByDifference(difference, points, lambda);
    for (size_t i = 0; i < points.size(); ++i) {
      (labels[i] == FeatureLabel::kForeground ? fg : bg).push_back(points[i]);
    }
  }
};

void BM_Prepare(benchmark::State& state) {
  const Pair pair = synthPair(state);
  const Params params;
  for (auto _ : state) benchmark::DoNotOptimize(prepareFrame(pair.cur, params));
}

void BM_Motion(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  for (auto _ : state) {
    benchmark::DoNotOptimize(estimateCameraMotion(in.prev, in.cur, in.motion.model, in.params, 0));
  }
}

void BM_Difference(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  const cv::Matx33d model = rescaleModel(in.motion.model, in.cur.seg_scale / in.cur.align_scale);
  for (auto _ : state) {
    benchmark::DoNotOptimize(compensatedDifference(in.prev.seg_smooth, in.cur.seg_smooth, model));
  }
}

// §3.2: eq. (3) at the features and the GMM refinement.
void BM_Classify(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  const double s = in.cur.seg_scale / in.cur.align_scale;
  std::vector<cv::Point2f> points;
  std::vector<cv::Vec3f> colours;
  for (const cv::Point2f& p : in.cur.features) {
    points.push_back(p * static_cast<float>(s));
    colours.emplace_back(in.cur.seg_bgr.at<cv::Vec3b>(points.back()));
  }
  for (auto _ : state) {
    const double lambda =
        chooseLambda(in.difference, staticPoints(in.motion, in.cur, in.cur.seg_scale), in.params);
    std::vector<FeatureLabel> labels = classifyByDifference(in.difference, points, lambda);
    refineByColour(colours, in.params.gmm_clusters, &labels);
    benchmark::DoNotOptimize(labels);
  }
}

void BM_GeodesicDistances(benchmark::State& state) {
  const StageInputs in(synthPair(state));
  cv::Mat colour;
  in.cur.seg_bgr.convertTo(colour, CV_32FC3, 1.0 / 255.0);
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
    const CutResult cut = geodesicGraphCut(in.cur.seg_bgr, in.fg, in.bg, in.params, solver);
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
