// The HTML report of `movseg bench --html` and `movseg eval --html`: one self-contained page
// that works offline — the score table, J per sequence and method as a chart, per-frame J curves,
// and per sequence the overlays of its worst frames. The charts are Chart.js's (from npm,
// report/package.json), inlined with report/report.js and report.css when the CLI is built.
#pragma once

#include <string>
#include <vector>

#include "eval/dataset.h"

namespace movseg::cli {

// A frame picture for the report: the prediction tinted red over the frame, the ground truth's
// outline in green, as a JPEG data URI.
struct Thumbnail {
  int frame = 0;
  double j = 0;
  std::string data_uri;
};

// One sequence segmented by one method.
struct ReportRun {
  std::string method;  // eval: the name of the prediction folder
  SequenceScore score;
  std::vector<Thumbnail> worst;  // the frames of lowest J, worst first
  double ms_per_frame = -1;      // < 0: not measured (eval)
};

// The run of `score`, with the thumbnails of its worst frames made from the frames, the
// predictions in `pred_dir` and the ground truth — now, while the predictions exist (bench
// deletes them once scored).
ReportRun reportRun(const GtSequence& sequence, const SequenceScore& score,
                    const std::string& pred_dir, const std::string& method, double ms_per_frame);

// Writes the page (atomically). `note` is a line under the title (machine, settings). Throws
// std::runtime_error when this build has no charting library (npm was missing).
void writeHtmlReport(const std::string& path, const std::string& title, const std::string& note,
                     const std::vector<ReportRun>& runs);

}  // namespace movseg::cli
