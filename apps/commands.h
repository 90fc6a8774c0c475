// The subcommands of build/movseg. Each add*Command registers its options and its callback;
// a callback reports failure by throwing std::exception with a one-line message: UsageError
// for a command line that cannot be run as given, anything else for a run that failed.
#pragma once

#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <opencv2/core/types.hpp>

#include "core/text.h"

namespace movseg::cli {

// Exit codes (README, docs/usage.md).
constexpr int kExitRunFailed = 1;    // bad input, a failed write, a decode error
constexpr int kExitUsage = 2;        // the command line: unknown option, bad value, bad paths
constexpr int kExitInterrupted = 130;  // SIGINT or SIGTERM, 128 + SIGINT as shells report it

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A size given as WIDTHxHEIGHT (or WIDTHXHEIGHT), e.g. 320x240; `option` names it in the
// UsageError thrown for anything else. Its range is the caller's to check.
cv::Size parseSize(const std::string& option, const std::string& text);

// Runs `interpret`, which turns a command's options into its settings before anything runs: an
// std::invalid_argument it throws names a value out of range, the command line's fault, and is
// rethrown as a UsageError (exit code 2).
template <typename Interpret>
void interpretOptions(Interpret&& interpret) {
  try {
    interpret();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

// Refuses each of `options` of `command` given an empty value (`--json ''`, `-o ''`): an empty
// name would otherwise mean "none", or the current folder, without a word. Throws UsageError
// "--json: the name is empty".
void refuseEmptyNames(const CLI::App& command, std::initializer_list<const char*> options);

// Claims the folder `dir` for a synthetic sequence (`synth`, `demo`). A folder
// that holds anything is refused unless `overwrite`, which first removes what such a sequence
// writes there (removeSynthSequence()) and the numbered pictures of `owned_folders`: a shorter
// sequence leaves no frame of a longer one behind, and a dataset named by mistake is not mixed
// with synthetic frames.
void claimSequenceFolder(const std::string& dir, bool overwrite,
                         std::initializer_list<const char*> owned_folders = {});

// Whether `path` is `base` or lies inside it, once both are made absolute and normal.
bool isSameOrInside(const std::string& path, const std::string& base);

// Whether `a` and `b` name one place, once both are made absolute and normal.
bool isSamePlace(const std::string& a, const std::string& b);

// Throws UsageError "OPTION and OPTION both name 'PATH'" when two of `outputs` (an option and its
// path; empty paths are not checked) are one place: the later write would replace the earlier.
void refuseSharedOutputs(std::initializer_list<std::pair<const char*, std::string>> outputs);

// The folder for temporary files: $TMPDIR, else /tmp. Throws std::runtime_error with one line
// when it is not a folder (a TMPDIR set to a missing path), asked for only by the commands that
// write there (`bench`'s scratch runs, `demo`'s default folder), so that the others never mind.
std::filesystem::path temporaryFolder();

// Throws CLI::RuntimeError(kExitInterrupted) after saying on stderr how far the run got, when
// a signal stopped it.
void throwIfInterrupted(int frames, bool interrupted);

// The help of --overwrite for `synth` and `demo`.
constexpr char kOverwriteSequenceHelp[] =
    "Replace the frames, masks and camera.jsonl of an earlier sequence in the folder (else a "
    "folder that holds files is refused)";

void addSegmentCommand(CLI::App& app);
void addSynthCommand(CLI::App& app);
void addDemoCommand(CLI::App& app);
void addEvalCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);

}  // namespace movseg::cli
