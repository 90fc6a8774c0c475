// movseg eval PRED GT [--format auto|plain|davis|segtrack|cdnet] [--json FILE] [--csv FILE]
//             [--html FILE]
// (metrics and layouts: src/eval/, docs/metrics.md)
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

#include "commands.h"
#include "eval/dataset.h"
#include "html_report.h"
#include "io/atomic_write.h"
#include "segment_run.h"

namespace movseg::cli {
namespace {

struct EvalOptions {
  std::string pred;
  std::string gt;
  std::string format = "auto";  // a key of gtFormatNames()
  std::string json_file;
  std::string csv_file;
  std::string html_file;
};

// "2 davis sequences", "1 cdnet sequence, 1 plain sequence".
std::string describeGroundTruth(const std::vector<GtSequence>& sequences) {
  std::map<std::string, int> counts;
  for (const GtSequence& sequence : sequences) ++counts[gtFormatName(sequence.format)];
  std::string text;
  for (const auto& [name, count] : counts) {
    text += (text.empty() ? "" : ", ") + std::to_string(count) + " " + name +
            (count == 1 ? " sequence" : " sequences");
  }
  return text;
}

// A sequence without a counted frame has no score, and a mean over the others would pass for
// the whole set's: fail, naming the first such sequence. Its ground truth has frames to score
// (requireFramesToScore()): their predictions are missing.
void requireCountedFrames(const std::vector<GtSequence>& sequences,
                          const std::vector<SequenceScore>& scores, const std::string& pred) {
  std::vector<size_t> unscored;
  for (size_t i = 0; i < scores.size(); ++i) {
    if (scores[i].counted().empty()) unscored.push_back(i);
  }
  if (unscored.empty()) return;
  const std::string more =
      unscored.size() > 1 ? " (nor for " + std::to_string(unscored.size() - 1) + " more)" : "";
  throw std::runtime_error("no predicted mask for sequence '" + scores[unscored.front()].name +
                           "' in '" + predictionDir(sequences[unscored.front()], pred) + "'" +
                           more);
}

// `movseg eval GT PRED` by mistake would score the ground truth against the predictions without
// a word. A prediction folder holds masks only; a ground-truth sequence comes with its video's
// frames: when PRED has them and GT does not, the two are swapped.
void rejectSwappedArguments(const EvalOptions& options, const std::vector<GtSequence>& truth) {
  for (const GtSequence& sequence : truth) {
    if (!sequence.video_frames.empty()) return;
  }
  std::vector<GtSequence> pred_as_truth;
  try {
    pred_as_truth = loadGroundTruth(options.pred, GtFormat::kAuto);
  } catch (const std::runtime_error&) {
    return;  // not ground truth at all
  }
  for (const GtSequence& sequence : pred_as_truth) {
    if (sequence.video_frames.empty()) continue;
    throw std::runtime_error("PRED '" + options.pred +
                             "' holds video frames and masks, like ground truth, and GT '" +
                             options.gt +
                             "' masks only: are they swapped? The order is movseg eval PRED GT");
  }
}

void writeReport(const EvalOptions& options, const std::vector<GtSequence>& sequences,
                 const std::vector<SequenceScore>& scores) {
  std::vector<ReportRun> runs;
  for (size_t i = 0; i < sequences.size(); ++i) {
    runs.push_back(reportRun(sequences[i], scores[i], predictionDir(sequences[i], options.pred),
                             folderName(options.pred), -1));
  }
  writeHtmlReport(options.html_file, "movseg eval: " + options.pred,
                  "predictions '" + options.pred + "' against the ground truth '" + options.gt +
                      "'",
                  runs);
}

// After SIGINT or SIGTERM (StopOnSignal), which the scoring heeds between sequences: nothing
// more is written. Files written before it are complete.
void throwIfStopped() {
  if (!StopOnSignal::stopped()) return;
  std::cerr << "movseg: interrupted; the files written so far are complete\n";
  throw CLI::RuntimeError(kExitInterrupted);
}

void runEval(const EvalOptions& options) {
  const StopOnSignal stop_on_signal;
  std::error_code error;
  if (!std::filesystem::is_directory(options.pred, error)) {
    throw std::runtime_error("prediction folder '" + options.pred + "' does not exist");
  }
  const std::vector<GtSequence> sequences =
      loadGroundTruth(options.gt, gtFormatNames().at(options.format));
  // Before the scoring rather than after it; none inside PRED or GT, nor inside a sequence's
  // folders where they are links out of them.
  std::vector<std::string> inputs = sequenceFolders(sequences, options.pred);
  inputs.insert(inputs.end(), {options.pred, options.gt});
  checkReportPaths(
      {{"--json", options.json_file}, {"--csv", options.csv_file}, {"--html", options.html_file}},
      inputs);
  rejectSwappedArguments(options, sequences);
  requireFramesToScore(sequences);
  const std::vector<SequenceScore> scores =
      scoreDataset(sequences, options.pred, &StopOnSignal::stopped);
  throwIfStopped();
  std::cout << "eval: " << describeGroundTruth(sequences) << " in '" << options.gt << "'\n"
            << formatScoreTable(scores);
  requireCountedFrames(sequences, scores, options.pred);
  if (!options.csv_file.empty()) writeTextAtomic(options.csv_file, scoresCsv(scores));
  if (!options.json_file.empty()) writeTextAtomic(options.json_file, scoresJson(scores));
  if (!options.html_file.empty()) writeReport(options, sequences, scores);
  throwIfStopped();
}

}  // namespace

void addEvalCommand(CLI::App& app) {
  auto options = std::make_shared<EvalOptions>();
  CLI::App* cmd = app.add_subcommand("eval", "Score predicted masks against ground truth");
  cmd->add_option("PRED", options->pred,
                  "Predicted masks (non-zero = foreground): a mask folder, or for a dataset GT "
                  "one folder per sequence (PRED/<sequence>/ or PRED/<sequence>/masks/)")
      ->required();
  cmd->add_option("GT", options->gt,
                  "Ground truth: a mask folder, a sequence (<seq>/masks/, ground-truth/, "
                  "groundtruth/) or a dataset folder of such sequences")
      ->required();
  std::vector<std::string> formats;
  for (const auto& entry : gtFormatNames()) formats.push_back(entry.first);
  cmd->add_option("--format", options->format, "Ground-truth layout")
      ->check(CLI::IsMember(formats))
      ->capture_default_str();
  cmd->add_option("--json", options->json_file, "Per-sequence means and per-frame scores as JSON");
  cmd->add_option("--html", options->html_file,
                  "Write a report page: the table, charts of J, each sequence's worst frames");
  cmd->add_option("--csv", options->csv_file,
                  "Per-frame scores: sequence,frame,J,F,error_rate,precision,recall,f1");
  cmd->callback([options, cmd] {
    refuseEmptyNames(*cmd, {"--json", "--csv", "--html"});
    runEval(*options);
  });
}

}  // namespace movseg::cli
