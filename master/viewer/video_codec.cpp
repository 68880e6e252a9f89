#include "viewer/video_codec.h"

#include <stdexcept>

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/error.h>
#include <libavutil/frame.h>
#include <libavutil/log.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace igi {
namespace {

std::string av_text(int error) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(error, text, sizeof text);
  return text;
}

// What both ends hold: a codec context, a YUV frame, a packet and the colour converter.
struct Codec {
  AVCodecContext* context = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* convert = nullptr;
  ~Codec() {
    sws_freeContext(convert);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&context);
  }
};

}  // namespace

bool have_h264_encoder() { return avcodec_find_encoder_by_name("libx264") != nullptr; }

struct VideoEncoder::State : Codec {
  int64_t pts = 0;
  double frames_per_second = 25.0;
};

namespace {

// The rate control's cap, and a VBV buffer of one frame's worth: no burst queues up behind it.
void set_rate(AVCodecContext* c, double mbit_per_second, double frames_per_second) {
  c->bit_rate = int64_t(mbit_per_second * 1e6);
  c->rc_max_rate = c->bit_rate;
  c->rc_buffer_size = int(double(c->bit_rate) / frames_per_second);
}

}  // namespace

VideoEncoder::VideoEncoder(int width, int height, double mbit_per_second, double frames_per_second)
    : state_(std::make_unique<State>()) {
  av_log_set_level(AV_LOG_ERROR);  // not x264's statistics on the master's terminal at every new stream
  const AVCodec* codec = avcodec_find_encoder_by_name("libx264");
  if (!codec) throw std::runtime_error("this build's libavcodec has no H.264 encoder (libx264)");
  if (width % 2 || height % 2) throw std::runtime_error("H.264 frames need an even width and height");
  AVCodecContext* c = state_->context = avcodec_alloc_context3(codec);
  c->width = width;
  c->height = height;
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->time_base = {1, std::max(1, int(frames_per_second + 0.5))};
  c->framerate = {c->time_base.den, 1};
  c->gop_size = 10 * c->time_base.den;  // a key frame every 10 s at most; a new viewer gets a new stream
  c->max_b_frames = 0;
  c->thread_count = 1;  // no frame threads: one frame in, one packet out
  state_->frames_per_second = frames_per_second;
  set_rate(c, mbit_per_second, frames_per_second);
  av_opt_set(c->priv_data, "preset", "ultrafast", 0);
  av_opt_set(c->priv_data, "tune", "zerolatency", 0);
  if (const int e = avcodec_open2(c, codec, nullptr); e < 0) throw std::runtime_error("libx264: " + av_text(e));
  state_->frame = av_frame_alloc();
  state_->frame->format = c->pix_fmt;
  state_->frame->width = width;
  state_->frame->height = height;
  if (av_frame_get_buffer(state_->frame, 0) < 0) throw std::runtime_error("libx264: no memory for a frame");
  state_->packet = av_packet_alloc();
  state_->convert = sws_getContext(width, height, AV_PIX_FMT_RGB24, width, height, AV_PIX_FMT_YUV420P,
                                   SWS_BILINEAR, nullptr, nullptr, nullptr);
  if (!state_->convert) throw std::runtime_error("swscale: cannot convert RGB to YUV 4:2:0");
}

VideoEncoder::~VideoEncoder() = default;

std::vector<uint8_t> VideoEncoder::encode(std::span<const uint8_t> rgb) {
  State& s = *state_;
  if (av_frame_make_writable(s.frame) < 0) throw std::runtime_error("libx264: frame not writable");
  const uint8_t* source[1] = {rgb.data()};
  const int stride[1] = {3 * s.context->width};
  sws_scale(s.convert, source, stride, 0, s.context->height, s.frame->data, s.frame->linesize);
  s.frame->pts = s.pts++;
  if (const int e = avcodec_send_frame(s.context, s.frame); e < 0) throw std::runtime_error("libx264: " + av_text(e));
  std::vector<uint8_t> unit;
  while (avcodec_receive_packet(s.context, s.packet) == 0) {
    unit.insert(unit.end(), s.packet->data, s.packet->data + s.packet->size);
    av_packet_unref(s.packet);
  }
  return unit;
}

void VideoEncoder::set_bit_rate(double mbit_per_second) {
  set_rate(state_->context, mbit_per_second, state_->frames_per_second);
}

double VideoEncoder::bit_rate() const { return double(state_->context->bit_rate) * 1e-6; }

struct VideoDecoder::State : Codec {
  int width = 0, height = 0;  // of the converter
};

VideoDecoder::VideoDecoder() : state_(std::make_unique<State>()) {
  const AVCodec* codec = avcodec_find_decoder(AV_CODEC_ID_H264);
  if (!codec) throw std::runtime_error("this build's libavcodec has no H.264 decoder");
  AVCodecContext* c = state_->context = avcodec_alloc_context3(codec);
  c->thread_count = 1;
  c->flags |= AV_CODEC_FLAG_LOW_DELAY;
  if (const int e = avcodec_open2(c, codec, nullptr); e < 0) throw std::runtime_error("H.264 decoder: " + av_text(e));
  state_->frame = av_frame_alloc();
  state_->packet = av_packet_alloc();
}

VideoDecoder::~VideoDecoder() = default;

std::optional<std::vector<uint8_t>> VideoDecoder::decode(std::span<const uint8_t> packet, int width, int height,
                                                        std::string& error) {
  State& s = *state_;
  std::vector<uint8_t> padded(packet.size() + AV_INPUT_BUFFER_PADDING_SIZE, 0);  // the parser reads past the end
  std::copy(packet.begin(), packet.end(), padded.begin());
  s.packet->data = padded.data();
  s.packet->size = int(packet.size());
  int e = avcodec_send_packet(s.context, s.packet);
  s.packet->data = nullptr;
  s.packet->size = 0;
  if (e >= 0) e = avcodec_receive_frame(s.context, s.frame);
  if (e < 0) {
    error = "Frame.pixels: H.264 does not decode (" + av_text(e) + ")";
    return std::nullopt;
  }
  if (s.frame->width != width || s.frame->height != height || s.frame->format != AV_PIX_FMT_YUV420P) {
    error = "Frame.pixels: H.264 frame of " + std::to_string(s.frame->width) + " x " +
            std::to_string(s.frame->height) + ", expected " + std::to_string(width) + " x " + std::to_string(height);
    return std::nullopt;
  }
  if (!s.convert || s.width != width || s.height != height) {
    sws_freeContext(s.convert);
    s.convert = sws_getContext(width, height, AV_PIX_FMT_YUV420P, width, height, AV_PIX_FMT_RGB24, SWS_BILINEAR,
                               nullptr, nullptr, nullptr);
    s.width = width;
    s.height = height;
  }
  std::vector<uint8_t> rgb(size_t(width) * size_t(height) * 3);
  uint8_t* target[1] = {rgb.data()};
  const int stride[1] = {3 * width};
  sws_scale(s.convert, s.frame->data, s.frame->linesize, 0, height, target, stride);
  av_frame_unref(s.frame);
  return rgb;
}

}  // namespace igi
