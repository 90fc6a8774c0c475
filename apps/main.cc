// build/movseg: segment moving objects, make synthetic test video, evaluate and benchmark.
#include <malloc.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <stdexcept>

#include <opencv2/core/utility.hpp>
#include <opencv2/core/utils/logger.hpp>

#include "commands.h"

namespace {

// Errors reach the user as one line of ours; FFmpeg's and OpenCV's own chatter ("moov atom not
// found", imread warnings) would add lines around it. An explicit environment setting wins.
void quietLibraries() {
  setenv("OPENCV_FFMPEG_LOGLEVEL", "-8", 0);  // AV_LOG_QUIET
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_ERROR);
}

// Writes report their errors instead of killing the process: a closed stdout (movseg ... | head)
// and a file-size limit (ulimit -f) become failed writes, not deaths by SIGPIPE or SIGXFSZ.
void reportFailedWrites() {
  std::signal(SIGPIPE, SIG_IGN);
  std::signal(SIGXFSZ, SIG_IGN);
}

int fail(int code, const std::exception& e) {
  std::cerr << "movseg: error: " << movseg::oneLine(e.what()) << std::endl;
  return code;
}

// Per-frame buffers of a few hundred kilobytes would otherwise be mapped from the kernel and
// given back on every frame (glibc serves large blocks with mmap and trims the heap's top), and
// faulting their pages in again cost a third of a run's time on a VM (docs/design.md). Kept in
// the heap, they are reused. The library leaves the process's allocator alone; programs that
// call it can do the same, or set GLIBC_TUNABLES.
void keepLargeBlocksInTheHeap() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's largest
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
}

bool standardOutputIsAPipe() {
  struct stat status {};
  return fstat(STDOUT_FILENO, &status) == 0 && S_ISFIFO(status.st_mode);
}

}  // namespace

int main(int argc, char** argv) {
  keepLargeBlocksInTheHeap();
  quietLibraries();
  reportFailedWrites();
  cv::setNumThreads(1);  // per-frame work is small; one core per stream is the design point
  CLI::App app{"movseg: moving object segmentation for freely moving cameras"};
  app.set_version_flag("--version", "movseg " MOVSEG_VERSION);
  app.require_subcommand(1);
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "movseg: error: " + movseg::oneLine(e.what()) + "\n";
  });
  movseg::cli::addSegmentCommand(app);
  movseg::cli::addSynthCommand(app);
  movseg::cli::addDemoCommand(app);
  movseg::cli::addEvalCommand(app);
  movseg::cli::addBenchCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help
    return app.exit(e);
  } catch (const CLI::RuntimeError& e) {  // a command's own exit code (an interrupted run)
    return e.get_exit_code();
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return movseg::cli::kExitUsage;
  } catch (const movseg::cli::UsageError& e) {
    return fail(movseg::cli::kExitUsage, e);
  } catch (const std::exception& e) {
    return fail(movseg::cli::kExitRunFailed, e);
  }
  // The tables of eval and bench, segment's summary: a full disk or a file-size limit under
  // them is a failed write like any other. A pipe whose reader left (`movseg eval ... | head`)
  // is the reader's choice.
  if (!std::cout.flush() && !standardOutputIsAPipe()) {
    return fail(movseg::cli::kExitRunFailed,
                std::runtime_error("cannot write to the standard output"));
  }
  return 0;
}
