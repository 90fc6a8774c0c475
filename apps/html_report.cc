#include "html_report.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <stdexcept>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/atomic_write.h"
#include "io/frame_source.h"
#include "io/json_text.h"

namespace movseg::cli {

// The page's assets, generated into the build tree from report/ (report/embed.cmake).
extern const unsigned char kChartJs[], kReportJs[], kReportCss[];
extern const std::size_t kChartJsSize, kReportJsSize, kReportCssSize;

namespace {

constexpr int kWorstFrames = 4;
// A thumbnail fits 160 x 320 pixels, its frame's shape kept: a mask 1000 times taller than
// wide made one taller than JPEG can encode.
constexpr int kThumbnailWidth = 160, kThumbnailHeight = 320;

std::string asset(const unsigned char* bytes, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(bytes), size);
}

std::string base64(const std::vector<uchar>& bytes) {
  static const char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = std::min<std::size_t>(3, bytes.size() - i);
    unsigned group = bytes[i] << 16;
    if (left > 1) group |= bytes[i + 1] << 8;
    if (left > 2) group |= bytes[i + 2];
    for (std::size_t d = 0; d < 4; ++d) {
      text += d <= left ? kDigits[(group >> (18 - 6 * d)) & 63] : '=';
    }
  }
  return text;
}

std::string escaped(const std::string& text) {
  std::string html;
  for (char c : utf8Text(text)) {
    switch (c) {
      case '&': html += "&amp;"; break;
      case '<': html += "&lt;"; break;
      case '>': html += "&gt;"; break;
      case '"': html += "&quot;"; break;
      default: html += c;
    }
  }
  return html;
}

// The frame under the masks: the video's, else a grey canvas (a plain mask folder has none).
cv::Mat backgroundOf(const GtSequence& sequence, int frame, cv::Size size) {
  const std::map<int, std::string> frames = numberedImages(sequence.frames_dir);
  const auto found = frames.find(frame);
  cv::Mat picture;
  // A frame that cannot be decoded (cut short, a header beyond the limits) is no error here.
  if (found != frames.end()) picture = decodeImage(found->second, cv::IMREAD_COLOR);
  if (picture.size() != size) picture = cv::Mat(size, CV_8UC3, cv::Scalar::all(96));
  return picture;
}

Thumbnail thumbnail(const GtSequence& sequence, const FrameScore& score,
                    const std::string& prediction) {
  const GtFrame& truth_frame = *std::find_if(
      sequence.frames.begin(), sequence.frames.end(),
      [&](const GtFrame& frame) { return frame.index == score.frame; });
  cv::Mat truth = readGtMask(sequence, truth_frame, nullptr);
  cv::Mat predicted = readMask(prediction);
  // Drawn at the thumbnail's size, so that the outline stays visible.
  const double scale = std::min(static_cast<double>(kThumbnailWidth) / truth.cols,
                                static_cast<double>(kThumbnailHeight) / truth.rows);
  const cv::Size size(std::max(1, static_cast<int>(truth.cols * scale)),
                      std::max(1, static_cast<int>(truth.rows * scale)));
  cv::Mat picture = backgroundOf(sequence, score.frame, truth.size());
  cv::resize(picture, picture, size, 0, 0, cv::INTER_AREA);
  cv::resize(truth, truth, size, 0, 0, cv::INTER_NEAREST);
  cv::resize(predicted, predicted, size, 0, 0, cv::INTER_NEAREST);
  cv::Mat tinted = picture.clone();
  tinted.setTo(cv::Scalar(0, 0, 255), predicted);
  cv::addWeighted(picture, 0.4, tinted, 0.6, 0, picture);
  std::vector<std::vector<cv::Point>> outline;
  cv::findContours(truth, outline, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  cv::drawContours(picture, outline, -1, cv::Scalar(0, 255, 0), 2);
  std::vector<uchar> jpeg;
  cv::imencode(".jpg", picture, jpeg, {cv::IMWRITE_JPEG_QUALITY, 85});
  return {score.frame, score.j, "data:image/jpeg;base64," + base64(jpeg)};
}

std::vector<std::string> methodsOf(const std::vector<ReportRun>& runs) {
  std::vector<std::string> methods;
  for (const ReportRun& run : runs) {
    if (std::find(methods.begin(), methods.end(), run.method) == methods.end()) {
      methods.push_back(run.method);
    }
  }
  return methods;
}

std::vector<std::string> sequencesOf(const std::vector<ReportRun>& runs) {
  std::vector<std::string> sequences;
  for (const ReportRun& run : runs) {
    if (std::find(sequences.begin(), sequences.end(), run.score.name) == sequences.end()) {
      sequences.push_back(run.score.name);
    }
  }
  return sequences;
}

std::string tableRow(const ScoreSummary& row, const std::string& method, double ms_per_frame,
                     bool timed, const std::string& css_class) {
  std::string html = "<tr" + (css_class.empty() ? "" : " class=\"" + css_class + "\"") + "><td>" +
                     escaped(row.name) + "</td><td class=\"text\">" + escaped(method) + "</td>";
  for (const std::string& cell :
       {std::to_string(row.frames), formatFixed(row.j, 3), formatFixed(row.j_recall, 3),
        formatFixed(row.f, 3), formatFixed(row.error_rate, 2), formatFixed(row.precision, 3),
        formatFixed(row.recall, 3), formatFixed(row.f1, 3)}) {
    html += "<td>" + cell + "</td>";
  }
  if (timed) html += "<td>" + formatFixed(ms_per_frame, 2) + "</td>";
  return html + "</tr>\n";
}

// The table: a row per run, then per method the mean over its sequences (each weighs the same).
std::string scoreTable(const std::vector<ReportRun>& runs) {
  const bool timed = runs.front().ms_per_frame >= 0;
  std::string html =
      "<table>\n<tr><th>sequence</th><th class=\"text\">method</th><th>frames</th><th>J</th>"
      "<th>J recall</th><th>F</th><th>error %</th><th>P</th><th>R</th><th>F1</th>" +
      std::string(timed ? "<th>ms/frame</th>" : "") + "</tr>\n";
  for (const ReportRun& run : runs) {
    html += tableRow(summarize(run.score), run.method, run.ms_per_frame, timed, "");
  }
  if (sequencesOf(runs).size() < 2) return html + "</table>\n";
  for (const std::string& method : methodsOf(runs)) {
    std::vector<ScoreSummary> rows;
    double ms = 0;
    for (const ReportRun& run : runs) {
      if (run.method != method) continue;
      rows.push_back(summarize(run.score));
      ms += run.ms_per_frame;
    }
    html += tableRow(meanOverSequences(rows, "mean"), method, ms / static_cast<double>(rows.size()),
                     timed, "mean");
  }
  return html + "</table>\n";
}

std::string canvasId(std::size_t sequence) { return "curve-" + std::to_string(sequence); }

// The figures the charts draw: J per sequence and method, and the per-frame J curves.
nlohmann::json chartData(const std::vector<ReportRun>& runs) {
  const std::vector<std::string> methods = methodsOf(runs);
  const std::vector<std::string> sequences = sequencesOf(runs);
  nlohmann::json j_by_method = nlohmann::json::object();
  nlohmann::json curves = nlohmann::json::array();
  for (const std::string& method : methods) {
    j_by_method[method] = nlohmann::json::array();
    for (std::size_t s = 0; s < sequences.size(); ++s) j_by_method[method].push_back(nullptr);
  }
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    nlohmann::json series = nlohmann::json::array();
    for (const ReportRun& run : runs) {
      if (run.score.name != sequences[s]) continue;
      const double j = run.score.meanJ();
      if (!std::isnan(j)) j_by_method[run.method][s] = j;
      nlohmann::json points = nlohmann::json::array();
      for (const FrameScore& frame : run.score.counted()) {
        points.push_back({{"x", frame.frame}, {"y", frame.j}});
      }
      series.push_back({{"method", run.method}, {"points", points}});
    }
    curves.push_back({{"canvas", canvasId(s)}, {"series", series}});
  }
  return {{"methods", methods}, {"sequences", sequences}, {"j", j_by_method}, {"curves", curves}};
}

std::string worstFramesStrip(const ReportRun& run) {
  std::string html = "<div class=\"strip\"><div class=\"method\">" + escaped(run.method) + "</div>";
  for (const Thumbnail& thumbnail : run.worst) {
    html += "<figure><img alt=\"frame " + std::to_string(thumbnail.frame) + "\" src=\"" +
            thumbnail.data_uri + "\"><figcaption>frame " + std::to_string(thumbnail.frame) +
            ", J " + formatFixed(thumbnail.j, 3) + "</figcaption></figure>";
  }
  return html + "</div>\n";
}

// Per sequence: its J curve, then each method's worst frames.
std::string sequenceSections(const std::vector<ReportRun>& runs) {
  std::string html;
  const std::vector<std::string> sequences = sequencesOf(runs);
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    html += "<h3>" + escaped(sequences[s]) + "</h3>\n<canvas class=\"curve\" id=\"" +
            canvasId(s) + "\"></canvas>\n";
    for (const ReportRun& run : runs) {
      if (run.score.name == sequences[s]) html += worstFramesStrip(run);
    }
  }
  return html;
}

// JSON inside <script>: "</script" would end the element and "<!--" change how it is read, so
// '<', '>' and '&', which JSON has only inside strings, are written as their \u escapes.
std::string scriptSafe(const std::string& json) {
  std::string safe;
  safe.reserve(json.size());
  for (const char c : json) {
    if (c == '<') {
      safe += "\\u003c";
    } else if (c == '>') {
      safe += "\\u003e";
    } else if (c == '&') {
      safe += "\\u0026";
    } else {
      safe += c;
    }
  }
  return safe;
}

}  // namespace

ReportRun reportRun(const GtSequence& sequence, const SequenceScore& score,
                    const std::string& pred_dir, const std::string& method, double ms_per_frame) {
  ReportRun run{method, score, {}, ms_per_frame};
  std::vector<FrameScore> frames = score.counted();
  std::stable_sort(frames.begin(), frames.end(),
                   [](const FrameScore& a, const FrameScore& b) { return a.j < b.j; });
  frames.resize(std::min<std::size_t>(frames.size(), kWorstFrames));
  const std::map<int, std::string> predictions = matchPredictions(sequence, pred_dir);
  for (const FrameScore& frame : frames) {
    run.worst.push_back(thumbnail(sequence, frame, predictions.at(frame.frame)));
  }
  return run;
}

void writeHtmlReport(const std::string& path, const std::string& title, const std::string& note,
                     const std::vector<ReportRun>& runs) {
  if (kChartJsSize == 0) {
    throw std::runtime_error("--html: this movseg was built without its charting library (npm "
                             "was missing): run scripts/install-deps.sh and rebuild");
  }
  if (runs.empty()) throw std::runtime_error("--html: no scores to report");
  const std::string page =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
      escaped(title) + "</title>\n<style>\n" + asset(kReportCss, kReportCssSize) +
      "</style>\n</head>\n<body>\n<h1>" + escaped(title) + "</h1>\n<p class=\"note\">" +
      escaped(note) + "</p>\n<h2>Scores</h2>\n" + scoreTable(runs) +
      "<p class=\"note\">J, F, error: over the frames after the first of each sequence (it has no "
      "previous frame). P, R, F1: of the foreground pixels summed over the sequence.</p>\n"
      "<h2>J per sequence</h2>\n<canvas class=\"overview\" id=\"j-by-sequence\"></canvas>\n"
      "<h2>Per frame</h2>\n<p class=\"note\">J of every frame; below, the frames of lowest J: the "
      "prediction in red over the frame, the ground truth's outline in green.</p>\n" +
      sequenceSections(runs) + "<script type=\"application/json\" id=\"movseg-data\">" +
      scriptSafe(jsonText(chartData(runs))) + "</script>\n<script>\n" +
      asset(kChartJs, kChartJsSize) + "\n</script>\n<script>\n" +
      asset(kReportJs, kReportJsSize) + "</script>\n</body>\n</html>\n";
  writeTextAtomic(path, page);
}

}  // namespace movseg::cli
