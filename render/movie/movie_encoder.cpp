#include "movie/movie_encoder.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/imgutils.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include "core/error.hpp"
#include "output/pending_file.hpp"

namespace bsmpm::render {

namespace {

std::string av_message(int code) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  av_strerror(code, buf, sizeof buf);
  return buf;
}

}  // namespace

struct MovieEncoder::Av {
  std::unique_ptr<PendingFile> file;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;
  SwsContext* scaler = nullptr;
  bool header_written = false;
  bool io_open = false;

  ~Av() {
    sws_freeContext(scaler);
    av_packet_free(&packet);
    av_frame_free(&frame);
    avcodec_free_context(&codec);
    if (format) {
      if (io_open) avio_closep(&format->pb);
      avformat_free_context(format);
    }
    // `file` goes last: it removes the temporary file unless finish() committed it.
  }

  // Sends `input` (nullptr: flush) and writes every packet the encoder returns.
  void encode(AVFrame* input, const std::string& path) {
    int rc = avcodec_send_frame(codec, input);
    if (rc < 0) throw IoError(path + ": H.264 encoding failed: " + av_message(rc));
    while (true) {
      rc = avcodec_receive_packet(codec, packet);
      if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return;
      if (rc < 0) throw IoError(path + ": H.264 encoding failed: " + av_message(rc));
      av_packet_rescale_ts(packet, codec->time_base, stream->time_base);
      packet->stream_index = stream->index;
      rc = av_interleaved_write_frame(format, packet);
      if (rc < 0) throw IoError(path + ": writing the movie failed: " + av_message(rc));
    }
  }
};

MovieEncoder::MovieEncoder(const std::string& path, const MovieSettings& settings)
    : av_(std::make_unique<Av>()), path_(path), settings_(settings) {
  if (settings.width < 2 || settings.height < 2 || settings.width % 2 || settings.height % 2)
    throw UsageError("a yuv420p movie needs even dimensions (got " + std::to_string(settings.width) + "x" +
                     std::to_string(settings.height) + ")");
  if (settings.fps < 1) throw UsageError("--fps must be at least 1");
  av_log_set_level(AV_LOG_ERROR);  // x264 and the muxer are chatty at the default level
  const AVCodec* x264 = avcodec_find_encoder_by_name("libx264");
  if (!x264) throw IoError("this FFmpeg has no libx264 encoder (install the Debian package libavcodec59 or ffmpeg)");

  Av& av = *av_;
  av.file = std::make_unique<PendingFile>(path);
  const std::string& temp = av.file->temp_path();
  // The temporary name does not end in .mp4, so name the muxer.
  int rc = avformat_alloc_output_context2(&av.format, nullptr, "mp4", temp.c_str());
  if (rc < 0 || !av.format) throw IoError(path + ": cannot set up the MP4 muxer: " + av_message(rc));
  av.stream = avformat_new_stream(av.format, nullptr);
  av.codec = avcodec_alloc_context3(x264);
  av.frame = av_frame_alloc();
  av.packet = av_packet_alloc();
  if (!av.stream || !av.codec || !av.frame || !av.packet) throw Error("FFmpeg: out of memory");

  AVCodecContext* c = av.codec;
  c->width = settings.width;
  c->height = settings.height;
  c->time_base = AVRational{1, settings.fps};
  c->framerate = AVRational{settings.fps, 1};
  c->pix_fmt = AV_PIX_FMT_YUV420P;
  c->gop_size = 2 * settings.fps;  // a key frame every 2 s: seeking in a talk stays quick
  c->max_b_frames = 2;
  // BT.709, limited range: what HD players assume; stated so that none guesses.
  c->color_primaries = AVCOL_PRI_BT709;
  c->color_trc = AVCOL_TRC_BT709;
  c->colorspace = AVCOL_SPC_BT709;
  c->color_range = AVCOL_RANGE_MPEG;
  if (av.format->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  av_opt_set(c->priv_data, "preset", settings.preset.c_str(), 0);
  av_opt_set(c->priv_data, "profile", "high", 0);
  av_opt_set_int(c->priv_data, "crf", settings.crf, 0);
  rc = avcodec_open2(c, x264, nullptr);
  if (rc < 0) throw IoError(path + ": cannot open the H.264 encoder: " + av_message(rc));
  rc = avcodec_parameters_from_context(av.stream->codecpar, c);
  if (rc < 0) throw IoError(path + ": cannot configure the movie stream: " + av_message(rc));
  av.stream->time_base = c->time_base;
  av.stream->avg_frame_rate = c->framerate;

  rc = avio_open(&av.format->pb, temp.c_str(), AVIO_FLAG_WRITE);
  if (rc < 0) throw IoError(path + ": cannot create the file: " + av_message(rc));
  av.io_open = true;
  AVDictionary* options = nullptr;
  av_dict_set(&options, "movflags", "+faststart", 0);  // the moov index before the data
  rc = avformat_write_header(av.format, &options);
  av_dict_free(&options);
  if (rc < 0) throw IoError(path + ": cannot write the movie header: " + av_message(rc));
  av.header_written = true;

  av.frame->format = c->pix_fmt;
  av.frame->width = c->width;
  av.frame->height = c->height;
  rc = av_frame_get_buffer(av.frame, 0);
  if (rc < 0) throw Error("FFmpeg: cannot allocate a frame: " + av_message(rc));
  av.scaler = sws_getContext(c->width, c->height, AV_PIX_FMT_RGB24, c->width, c->height, AV_PIX_FMT_YUV420P,
                             SWS_BICUBIC | SWS_ACCURATE_RND | SWS_FULL_CHR_H_INP, nullptr, nullptr, nullptr);
  if (!av.scaler) throw Error("FFmpeg: cannot set up the RGB to YUV conversion");
  // RGB in full range; YUV out with BT.709 coefficients in limited range, matching the tags.
  const int* bt709 = sws_getCoefficients(SWS_CS_ITU709);
  sws_setColorspaceDetails(av.scaler, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);
}

MovieEncoder::~MovieEncoder() = default;

void MovieEncoder::add_frame(const Image& image) {
  if (image.width() != settings_.width || image.height() != settings_.height)
    throw UsageError("movie frame is " + std::to_string(image.width()) + "x" + std::to_string(image.height()) +
                     ", the movie " + std::to_string(settings_.width) + "x" + std::to_string(settings_.height));
  Av& av = *av_;
  const int rc = av_frame_make_writable(av.frame);
  if (rc < 0) throw Error("FFmpeg: cannot reuse the frame buffer: " + av_message(rc));
  const std::uint8_t* src[1] = {image.data()};
  const int stride[1] = {static_cast<int>(image.row_bytes())};
  sws_scale(av.scaler, src, stride, 0, image.height(), av.frame->data, av.frame->linesize);
  av.frame->pts = frames_++;
  av.encode(av.frame, path_);
}

void MovieEncoder::finish() {
  Av& av = *av_;
  av.encode(nullptr, path_);
  const int rc = av_write_trailer(av.format);  // with faststart, moves the index to the front
  if (rc < 0) throw IoError(path_ + ": cannot finish the movie: " + av_message(rc));
  avio_closep(&av.format->pb);
  av.io_open = false;
  av.file->commit();
}

}  // namespace bsmpm::render

// The module's entry point (movie_writer.hpp): the one symbol bsmpm_movie.so exports.
extern "C" __attribute__((visibility("default"))) bsmpm::render::MovieWriter* bsmpm_open_movie(
    const std::string& path, const bsmpm::render::MovieSettings& settings) {
  return new bsmpm::render::MovieEncoder(path, settings);
}
