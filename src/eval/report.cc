// The reports of scores: the printed table, CSV and JSON (declared in dataset.h).
#include "eval/dataset.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "core/text.h"
#include "io/json_text.h"

namespace movseg {
namespace {

constexpr size_t kColumnWidth = 9;

const char* const kFirstFrameNote =
    "The first frame of each sequence is not counted (no previous frame, so no motion cue).";
const char* const kLegend =
    "J recall: share of frames with J > 0.5. Error: mislabelled pixels in % (eq. 12).\n"
    "P, R, F1: of the foreground pixels summed over the sequence.";

std::string padLeft(const std::string& text, size_t width) {
  return std::string(width - std::min(width, text.size()), ' ') + text;
}

std::string tableLine(const std::vector<std::string>& cells, size_t name_width) {
  std::string line =
      cells[0] + std::string(name_width - std::min(name_width, cells[0].size()), ' ');
  for (size_t i = 1; i < cells.size(); ++i) line += padLeft(cells[i], kColumnWidth);
  return line + "\n";
}

std::vector<std::string> tableCells(const ScoreSummary& row) {
  return {oneLine(row.name),
          std::to_string(row.frames),
          std::to_string(row.skipped),
          std::to_string(row.missing),
          formatFixed(row.j, 3),
          formatFixed(row.j_recall, 3),
          formatFixed(row.f, 3),
          formatFixed(row.error_rate, 2),
          formatFixed(row.precision, 3),
          formatFixed(row.recall, 3),
          formatFixed(row.f1, 3)};
}

std::vector<ScoreSummary> summaries(const std::vector<SequenceScore>& scores) {
  std::vector<ScoreSummary> rows;
  for (const SequenceScore& score : scores) rows.push_back(summarize(score));
  return rows;
}

std::string positionNote(const std::vector<SequenceScore>& scores) {
  std::string names;
  for (const SequenceScore& score : scores) {
    if (score.matched_by_position) names += (names.empty() ? "" : ", ") + oneLine(score.name);
  }
  if (names.empty()) return "";
  return "Predictions numbered from 00000 matched to frames by their position in the frames "
         "folder: " +
         names + ".\n";
}

// Scores in CSV and JSON: six significant digits.
std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

nlohmann::json summaryJson(const ScoreSummary& row) {
  return {{"name", row.name},
          {"frames", row.frames},
          {"skipped", row.skipped},
          {"missing", row.missing},
          {"J", row.j},
          {"J_recall", row.j_recall},
          {"F", row.f},
          {"error_rate", row.error_rate},
          {"precision", row.precision},
          {"recall", row.recall},
          {"f1", row.f1}};
}

nlohmann::json frameJson(const FrameScore& frame) {
  return {{"frame", frame.frame},
          {"J", frame.j},
          {"F", frame.f},
          {"error_rate", frame.error_rate},
          {"precision", frame.precision()},
          {"recall", frame.recall()},
          {"f1", frame.f1()},
          {"tp", frame.tp},
          {"fp", frame.fp},
          {"fn", frame.fn},
          {"tn", frame.tn}};
}

}  // namespace

std::string formatFixed(double value, int decimals) {
  if (std::isnan(value)) return "-";
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

std::string formatScoreTable(const std::vector<SequenceScore>& scores) {
  std::vector<ScoreSummary> rows = summaries(scores);
  if (rows.size() > 1) rows.push_back(meanOverSequences(rows, "mean"));
  size_t name_width = std::string("sequence").size();
  for (const ScoreSummary& row : rows) name_width = std::max(name_width, row.name.size());
  std::string table = tableLine(
      {"sequence", "frames", "skipped", "missing", "J", "J recall", "F", "error %", "P", "R", "F1"},
      name_width);
  for (const ScoreSummary& row : rows) table += tableLine(tableCells(row), name_width);
  return table + kFirstFrameNote + "\n" + kLegend + "\n" + positionNote(scores);
}

std::string scoresCsv(const std::vector<SequenceScore>& scores) {
  std::string csv = "sequence,frame,J,F,error_rate,precision,recall,f1\n";
  for (const SequenceScore& score : scores) {
    for (const FrameScore& frame : score.counted()) {
      csv += csvField(score.name) + "," + std::to_string(frame.frame) + "," + number(frame.j) +
             "," + number(frame.f) + "," + number(frame.error_rate) + "," +
             number(frame.precision()) + "," + number(frame.recall()) + "," + number(frame.f1()) +
             "\n";
    }
  }
  return csv;
}

std::string scoresJson(const std::vector<SequenceScore>& scores) {
  nlohmann::json sequences = nlohmann::json::array();
  for (const SequenceScore& score : scores) {
    nlohmann::json entry = summaryJson(summarize(score));
    entry["first_frame"] = score.first_frame;
    entry["matched_by_position"] = score.matched_by_position;
    entry["per_frame"] = nlohmann::json::array();
    for (const FrameScore& frame : score.counted()) entry["per_frame"].push_back(frameJson(frame));
    sequences.push_back(entry);
  }
  const nlohmann::json report = {
      {"first_frame_counted", false},
      {"sequences", sequences},
      {"mean", summaryJson(meanOverSequences(summaries(scores), "mean"))}};
  return jsonText(report, 2) + "\n";
}

}  // namespace movseg
