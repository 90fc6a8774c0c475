#include "io/video_decoder.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <opencv2/core.hpp>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/display.h>
#include <libswscale/swscale.h>
}

namespace movseg {
namespace {

// The decoder inside an FFmpeg call on this thread (FFmpeg logs through one global callback).
thread_local VideoDecoder* t_calling = nullptr;

// A decoder's own messages are counted, never printed (the CLI speaks in one line of its own);
// everyone else's take FFmpeg's default path.
extern "C" void onFfmpegLog(void* context, int level, const char* format, va_list args) {
  if (t_calling == nullptr) {
    av_log_default_callback(context, level, format, args);
    return;
  }
  if (level > AV_LOG_ERROR) return;
  char text[256];
  std::vsnprintf(text, sizeof text, format, args);
  t_calling->noteLogMessage(text);
}

extern "C" int onFfmpegPoll(void* decoder) {
  return static_cast<VideoDecoder*>(decoder)->shouldGiveUp() ? 1 : 0;
}

// While a decoder calls FFmpeg. The callback is set on every call because OpenCV's FFmpeg
// backend sets its own when it first opens a file or writer.
class FfmpegCall {
 public:
  explicit FfmpegCall(VideoDecoder* decoder) {
    av_log_set_callback(onFfmpegLog);
    t_calling = decoder;
  }
  ~FfmpegCall() { t_calling = nullptr; }
};

std::string errorText(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

int clampedCount(double count) {
  return std::isfinite(count) && count > 0 ? static_cast<int>(std::min<double>(count, INT_MAX)) : -1;
}

}  // namespace

// A pipe's bytes for FFmpeg, read as they come. FFmpeg's own file protocol opens and reads a
// FIFO with blocking calls, which no deadline and no signal interrupt: a FIFO without a writer,
// or one whose writer stalls, would hang the run for ever. Opened without waiting for a writer,
// polled in slices of 50 ms, between which the decoder's deadline and stop flag are asked. Outside
// the anonymous namespace: VideoDecoder::FFmpeg, of external linkage, holds one.
class FifoInput {
 public:
  FifoInput(const std::string& path, VideoDecoder* decoder) : decoder_(decoder) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error(std::strerror(errno));
    constexpr int kBufferSize = 1 << 16;
    auto* buffer = static_cast<unsigned char*>(av_malloc(kBufferSize));
    io_ = buffer == nullptr ? nullptr
                            : avio_alloc_context(buffer, kBufferSize, 0, this, readSome, nullptr, nullptr);
    if (io_ == nullptr) {
      av_free(buffer);
      ::close(fd_);
      throw std::bad_alloc();
    }
  }
  ~FifoInput() {
    av_freep(&io_->buffer);
    avio_context_free(&io_);
    ::close(fd_);
  }
  FifoInput(const FifoInput&) = delete;
  FifoInput& operator=(const FifoInput&) = delete;
  AVIOContext* io() const { return io_; }

 private:
  // What FFmpeg asks for: up to `size` bytes, AVERROR_EOF once the writer has hung up,
  // AVERROR_EXIT at the deadline or a stop.
  static int readSome(void* opaque, uint8_t* buffer, int size) {
    auto* self = static_cast<FifoInput*>(opaque);
    for (;;) {
      if (self->decoder_->shouldGiveUp()) return AVERROR_EXIT;
      pollfd watch{self->fd_, POLLIN, 0};
      const int ready = ::poll(&watch, 1, 50);
      if (ready < 0 && errno != EINTR) return AVERROR(errno);
      if (ready <= 0) continue;
      const ssize_t n = ::read(self->fd_, buffer, static_cast<size_t>(size));
      if (n > 0) return static_cast<int>(n);
      if (n == 0 && (watch.revents & POLLHUP) != 0) return AVERROR_EOF;
      if (n < 0 && errno != EAGAIN && errno != EINTR) return AVERROR(errno);
    }
  }

  VideoDecoder* decoder_;
  int fd_ = -1;
  AVIOContext* io_ = nullptr;
};

struct VideoDecoder::FFmpeg {
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVFrame* frame = av_frame_alloc();
  AVPacket* packet = av_packet_alloc();
  SwsContext* sws = nullptr;
  std::unique_ptr<FifoInput> fifo;  // the input's bytes when it is a FIFO; outlives `format`
  int stream = -1;
  ~FFmpeg() {
    sws_freeContext(sws);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
  }
};

VideoDecoder::VideoDecoder(const std::string& url, const DecoderLimits& limits)
    : ff_(std::make_unique<FFmpeg>()), limits_(limits) {
  if (ff_->frame == nullptr || ff_->packet == nullptr) throw std::bad_alloc();
  open(url);
}

VideoDecoder::~VideoDecoder() = default;

void VideoDecoder::open(const std::string& url) {
  const FfmpegCall call(this);
  restartDeadline();
  const auto fail = [this](int code) {
    throw std::runtime_error(timed_out_ ? "no answer within the timeout"
                             : shouldGiveUp() ? "stopped"
                                              : errorText(code));
  };
  ff_->format = avformat_alloc_context();
  if (ff_->format == nullptr) throw std::bad_alloc();
  ff_->format->interrupt_callback = {onFfmpegPoll, this};
  std::error_code error;
  if (std::filesystem::is_fifo(url, error)) {
    ff_->fifo = std::make_unique<FifoInput>(url, this);
    ff_->format->pb = ff_->fifo->io();
    ff_->format->flags |= AVFMT_FLAG_CUSTOM_IO;
  }
  int r = avformat_open_input(&ff_->format, url.c_str(), nullptr, nullptr);  // frees on failure
  if (r < 0) fail(r);
  if ((r = avformat_find_stream_info(ff_->format, nullptr)) < 0) fail(r);
  const AVCodec* codec = nullptr;
  ff_->stream = av_find_best_stream(ff_->format, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (ff_->stream < 0) {
    throw std::runtime_error(ff_->stream == AVERROR_DECODER_NOT_FOUND ? "no decoder for its video"
                                                                      : "no video stream");
  }
  const AVStream* stream = ff_->format->streams[ff_->stream];
  ff_->codec = avcodec_alloc_context3(codec);
  if (ff_->codec == nullptr) throw std::bad_alloc();
  if ((r = avcodec_parameters_to_context(ff_->codec, stream->codecpar)) < 0) fail(r);
  ff_->codec->thread_count = 1;  // one core per stream is the design point
  if (limits_.max_pixels > 0) ff_->codec->max_pixels = limits_.max_pixels;
  if ((r = avcodec_open2(ff_->codec, codec, nullptr)) < 0) fail(r);

  const AVRational rate = stream->avg_frame_rate.num > 0 ? stream->avg_frame_rate : stream->r_frame_rate;
  fps_ = rate.num > 0 && rate.den > 0 ? av_q2d(rate) : 0;
  if (stream->nb_frames > 0) {
    expected_frames_ = clampedCount(static_cast<double>(stream->nb_frames));
    exact_count_ = true;
  } else {
    const double seconds = stream->duration != AV_NOPTS_VALUE
                               ? static_cast<double>(stream->duration) * av_q2d(stream->time_base)
                           : ff_->format->duration != AV_NOPTS_VALUE
                               ? static_cast<double>(ff_->format->duration) / AV_TIME_BASE
                               : 0;
    expected_frames_ = clampedCount(std::round(seconds * fps_));
    if (seconds > 0) duration_seconds_ = seconds;
  }
  const uint8_t* matrix = av_stream_get_side_data(stream, AV_PKT_DATA_DISPLAYMATRIX, nullptr);
  if (matrix != nullptr) rotation_ = av_display_rotation_get(reinterpret_cast<const int32_t*>(matrix));
}

bool VideoDecoder::read(cv::Mat* bgr) {
  const FfmpegCall call(this);
  // timed_out_ stays set once a read hit the deadline: FFmpeg's I/O is dead from then on, and a
  // demuxer such as MPEG-TS first hands out the packets it buffered and then reports an end of
  // file, which would pass for the stream's end.
  restartDeadline();
  for (;;) {
    const int r = avcodec_receive_frame(ff_->codec, ff_->frame);
    if (r == 0) {
      noteTimestamp();
      if (ff_->frame->decode_error_flags != 0 || (ff_->frame->flags & AV_FRAME_FLAG_CORRUPT) != 0) {
        noteError("a frame decoded with errors");
      }
      convert(bgr);
      return true;
    }
    if (r == AVERROR_EOF) return false;
    if (r != AVERROR(EAGAIN)) noteError(r);
    if (!sendNextPacket()) return false;
  }
}

bool VideoDecoder::sendNextPacket() {
  if (draining_) return false;
  for (;;) {
    const int r = av_read_frame(ff_->format, ff_->packet);
    if (r < 0) {
      if (r == AVERROR_EXIT || shouldGiveUp()) return false;  // the deadline or a stop
      if (r != AVERROR_EOF) noteError(r);
      draining_ = true;
      avcodec_send_packet(ff_->codec, nullptr);
      return true;
    }
    const bool ours = ff_->packet->stream_index == ff_->stream;
    const int sent = ours ? avcodec_send_packet(ff_->codec, ff_->packet) : 0;
    av_packet_unref(ff_->packet);
    if (sent < 0) noteError(sent);
    if (ours) return true;
  }
}

void VideoDecoder::noteTimestamp() {
  const AVStream* stream = ff_->format->streams[ff_->stream];
  const int64_t at = ff_->frame->best_effort_timestamp;
  if (at == AV_NOPTS_VALUE) return;
  const int64_t start = stream->start_time != AV_NOPTS_VALUE ? stream->start_time : 0;
  reached_seconds_ =
      std::max(reached_seconds_, static_cast<double>(at - start) * av_q2d(stream->time_base));
}

void VideoDecoder::convert(cv::Mat* bgr) {
  const AVFrame* f = ff_->frame;
  ff_->sws = sws_getCachedContext(ff_->sws, f->width, f->height, static_cast<AVPixelFormat>(f->format),
                                  f->width, f->height, AV_PIX_FMT_BGR24, SWS_BICUBIC, nullptr,
                                  nullptr, nullptr);
  if (ff_->sws == nullptr) {
    throw std::runtime_error("cannot convert a " + std::to_string(f->width) + "x" +
                             std::to_string(f->height) + " frame to BGR");
  }
  // swscale's SIMD converters write whole blocks of pixels: a 24x16 yuv420p frame wrote 24 bytes
  // past a packed buffer's end. Rows padded to 16 pixels, and a spare row, take the excess.
  const int padded_width = (f->width + 15) / 16 * 16;
  cv::Mat buffer(f->height + 1, padded_width, CV_8UC3);
  cv::Mat out = buffer(cv::Rect(0, 0, f->width, f->height));
  uint8_t* planes[4] = {out.data, nullptr, nullptr, nullptr};
  const int strides[4] = {static_cast<int>(out.step), 0, 0, 0};
  sws_scale(ff_->sws, f->data, f->linesize, 0, f->height, planes, strides);
  av_frame_unref(ff_->frame);
  // The display matrix turns counter-clockwise; phone videos store portrait frames turned.
  const int clockwise = std::isfinite(rotation_) ? ((-static_cast<int>(std::lround(rotation_)) % 360) + 360) % 360 : 0;
  if (clockwise == 90) cv::rotate(out, out, cv::ROTATE_90_CLOCKWISE);
  if (clockwise == 180) cv::rotate(out, out, cv::ROTATE_180);
  if (clockwise == 270) cv::rotate(out, out, cv::ROTATE_90_COUNTERCLOCKWISE);
  *bgr = out;
}

void VideoDecoder::noteLogMessage(const std::string& text) {
  std::string line = text;
  while (!line.empty() && (line.back() == '\n' || line.back() == '\r' || line.back() == ' ')) line.pop_back();
  noteError(line);
  logged_ = true;
}

void VideoDecoder::noteError(const std::string& text) {
  ++errors_;
  last_error_ = text;
}

// A failed call counts unless FFmpeg already said why during this read.
void VideoDecoder::noteError(int code) {
  if (!logged_) noteError(errorText(code));
}

bool VideoDecoder::shouldGiveUp() {
  if (limits_.stop != nullptr && limits_.stop->load()) return true;
  if (limits_.timeout.count() > 0 && std::chrono::steady_clock::now() > deadline_) timed_out_ = true;
  return timed_out_;
}

void VideoDecoder::restartDeadline() {
  logged_ = false;
  deadline_ = std::chrono::steady_clock::now() + limits_.timeout;
}

}  // namespace movseg
