#include "element.h"

#include <map>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <gst/video/video.h>
#include <opencv2/core.hpp>

#include "io/overlay.h"
#include "movseg/fields.h"
#include "movseg/segmenter.h"
#include "properties.h"

GST_DEBUG_CATEGORY_STATIC(movseg_debug);
#define GST_CAT_DEFAULT movseg_debug

namespace {

// What comes out of the element.
enum class Mode { kMask, kOverlay };

#define MOVSEG_INPUT_FORMATS "{ BGR, BGRx, GRAY8 }"

// Property ids: 0 is reserved by GObject; then `mode`, `post-messages`, `ignore`, and the
// parameters.
enum { kPropMode = 1, kPropPostMessages, kPropIgnore, kFirstParamProp };

// The element's state, a C++ object behind the GObject instance. Properties are set from the
// application's thread while frames run on the streaming thread: `lock` guards the settings.
struct State {
  std::mutex lock;
  movseg::Params params;
  std::map<std::size_t, std::string> refused;  // by parameter: why its last value was refused
  bool params_changed = true;   // the segmenter is (re)made with the settings at the next frame
  Mode mode = Mode::kMask;
  bool post_messages = true;
  std::string ignore;                     // the `ignore` property as given
  std::vector<cv::Rect2d> ignored;        // ... as read
  std::string ignore_refused;             // why its last value was refused
  bool ignore_changed = false;            // given to the segmenter at the next frame

  std::optional<movseg::Segmenter> segmenter;  // streaming thread only
  cv::Size region_size;                        // the frame size the region was last drawn at
  guint64 frame = 0;
};

}  // namespace

struct _GstMovseg {
  GstVideoFilter parent;
  State* state;
};

G_DEFINE_TYPE(GstMovseg, gst_movseg, GST_TYPE_VIDEO_FILTER)

namespace {

GType modeType() {
  static GType type = 0;
  if (type == 0) {
    static const GEnumValue values[] = {
        {static_cast<gint>(Mode::kMask), "the mask of what moves (GRAY8, 0 / 255)", "mask"},
        {static_cast<gint>(Mode::kOverlay),
         "the mask tinted over the frame, features as dots (BGR)", "overlay"},
        {0, nullptr, nullptr}};
    type = g_enum_register_static("GstMovsegMode", values);
  }
  return type;
}

State& stateOf(gpointer object) { return *GST_MOVSEG(object)->state; }

// Whether `id` names a property of the element.
bool isPropertyId(guint id) {
  return (id >= kPropMode && id < kFirstParamProp) ||
         (id >= kFirstParamProp && id - kFirstParamProp < movseg::paramFields().size());
}

// A refused text, set before the stream starts, is reported when it starts, as a refused
// parameter is (it reads back as given); until a good one replaces it the region stays as it
// was. Set while the stream runs, it is only refused.
void setIgnore(State* state, const char* given, bool running) {
  const std::string text = given == nullptr ? "" : given;
  try {
    state->ignored = movseg::gst::parseIgnoredRectangles(text);
    state->ignore = text;
    state->ignore_refused.clear();
    state->ignore_changed = true;
  } catch (const std::invalid_argument& e) {
    if (running) throw;
    state->ignore = text;
    state->ignore_refused = e.what();
  }
}

// Sets a property under the lock. A value refused while the stream runs throws
// std::invalid_argument and leaves the old one; refused before, it is kept to fail the start.
void setLocked(State* state, guint id, const GValue* value, bool running) {
  switch (id) {
    case kPropMode: state->mode = static_cast<Mode>(g_value_get_enum(value)); return;
    case kPropPostMessages: state->post_messages = g_value_get_boolean(value); return;
    case kPropIgnore: setIgnore(state, g_value_get_string(value), running); return;
    default: break;
  }
  const std::size_t field = id - kFirstParamProp;
  try {
    movseg::gst::setParamProperty(&state->params, field, value);
    state->refused.erase(field);
    state->params_changed = true;
  } catch (const std::invalid_argument& e) {
    if (running) throw;
    state->refused[field] = e.what();  // reported when the stream starts, as an error
  }
}

// A refused value is an error when the stream starts (start()); set while it runs, the old
// value stays and a warning on the bus says why (posted without the lock, which a bus handler
// reading a property would wait for). A new mode takes effect when the output caps are
// negotiated again, which it asks for.
void setProperty(GObject* object, guint id, const GValue* value, GParamSpec* spec) {
  if (!isPropertyId(id)) {
    G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, spec);
    return;
  }
  State& state = stateOf(object);
  const bool running = GST_STATE(object) > GST_STATE_READY;
  std::string refused;
  {
    const std::lock_guard<std::mutex> lock(state.lock);
    try {
      setLocked(&state, id, value, running);
    } catch (const std::invalid_argument& e) {
      refused = e.what();
    }
  }
  if (!refused.empty()) {
    GST_ELEMENT_WARNING(object, LIBRARY, SETTINGS, ("%s", refused.c_str()),
                        ("set while the stream runs: the earlier value stays"));
  }
  if (id == kPropMode) gst_base_transform_reconfigure_src(GST_BASE_TRANSFORM(object));
}

void getProperty(GObject* object, guint id, GValue* value, GParamSpec* spec) {
  State& state = stateOf(object);
  const std::lock_guard<std::mutex> lock(state.lock);
  switch (id) {
    case kPropMode: g_value_set_enum(value, static_cast<gint>(state.mode)); return;
    case kPropPostMessages: g_value_set_boolean(value, state.post_messages); return;
    case kPropIgnore: g_value_set_string(value, state.ignore.c_str()); return;
    default: break;
  }
  if (!isPropertyId(id)) {
    G_OBJECT_WARN_INVALID_PROPERTY_ID(object, id, spec);
    return;
  }
  movseg::gst::getParamProperty(state.params, id - kFirstParamProp, value);
}

// A refused property value stops the stream before it starts, naming the parameter (posted
// without the lock, as every message of the element's is).
gboolean start(GstBaseTransform* transform) {
  State& state = stateOf(transform);
  std::string reason;
  {
    const std::lock_guard<std::mutex> lock(state.lock);
    state.frame = 0;
    state.segmenter.reset();
    state.params_changed = true;
    if (state.refused.empty() && state.ignore_refused.empty()) return TRUE;
    reason = state.refused.empty() ? state.ignore_refused : state.refused.begin()->second;
  }
  GST_ELEMENT_ERROR(transform, LIBRARY, SETTINGS, ("%s", reason.c_str()), (nullptr));
  return FALSE;
}

gboolean sinkEvent(GstBaseTransform* transform, GstEvent* event) {
  if (GST_EVENT_TYPE(event) == GST_EVENT_FLUSH_STOP) {
    State& state = stateOf(transform);
    if (state.segmenter) state.segmenter->reset();  // after a seek the frames are no sequence
  }
  return GST_BASE_TRANSFORM_CLASS(gst_movseg_parent_class)->sink_event(transform, event);
}

GstCaps* outputFormat(Mode mode) {
  return gst_caps_from_string(mode == Mode::kMask ? "video/x-raw, format=GRAY8"
                                                  : "video/x-raw, format=BGR");
}

// Sink caps -> the same video in the mode's output format; source caps -> the same video in
// any input format. Everything but the format (size, rate, aspect) passes unchanged.
GstCaps* transformCaps(GstBaseTransform* transform, GstPadDirection direction, GstCaps* caps,
                       GstCaps* filter) {
  Mode mode;
  {
    State& state = stateOf(transform);
    const std::lock_guard<std::mutex> lock(state.lock);
    mode = state.mode;
  }
  GstCaps* output_format = outputFormat(mode);
  GstCaps* formatless = direction == GST_PAD_SRC ? gst_caps_intersect(caps, output_format)
                                                 : gst_caps_copy(caps);
  for (guint i = 0; i < gst_caps_get_size(formatless); ++i) {
    gst_structure_remove_fields(gst_caps_get_structure(formatless, i), "format", "colorimetry",
                                "chroma-site", nullptr);
  }
  GstCaps* formats = direction == GST_PAD_SINK
                         ? gst_caps_ref(output_format)
                         : gst_caps_from_string("video/x-raw, format=" MOVSEG_INPUT_FORMATS);
  GstCaps* result = gst_caps_intersect(formatless, formats);
  gst_caps_unref(formats);
  gst_caps_unref(formatless);
  gst_caps_unref(output_format);
  if (filter != nullptr) {
    GstCaps* filtered = gst_caps_intersect_full(filter, result, GST_CAPS_INTERSECT_FIRST);
    gst_caps_unref(result);
    result = filtered;
  }
  return result;
}

// The segmenter with the current settings, (re)made when they changed: a new stream start. Its
// ignored region is drawn at the frame's size, again when either changes.
// Throws what the segmenter's constructor and setIgnoredRegion() throw.
movseg::Segmenter* segmenterFor(GstVideoFilter* filter, cv::Size frame_size,
                                bool* post_messages) {
  State& state = stateOf(filter);
  const std::lock_guard<std::mutex> lock(state.lock);
  *post_messages = state.post_messages;
  if (state.params_changed || !state.segmenter) {
    state.params_changed = false;
    state.segmenter.emplace(state.params);
    state.region_size = cv::Size();
  }
  if (state.ignore_changed || state.region_size != frame_size) {
    state.ignore_changed = false;
    state.region_size = frame_size;
    state.segmenter->setIgnoredRegion(movseg::gst::ignoredRegion(state.ignored, frame_size));
  }
  return &*state.segmenter;
}

// A cv::Mat over a frame's pixels (rows may be padded).
cv::Mat matOf(GstVideoFrame* frame) {
  const int type = GST_VIDEO_FRAME_N_COMPONENTS(frame) == 1 ? CV_8UC1
                   : GST_VIDEO_FRAME_FORMAT(frame) == GST_VIDEO_FORMAT_BGRx ? CV_8UC4
                                                                             : CV_8UC3;
  return cv::Mat(GST_VIDEO_FRAME_HEIGHT(frame), GST_VIDEO_FRAME_WIDTH(frame), type,
                 GST_VIDEO_FRAME_PLANE_DATA(frame, 0),
                 static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(frame, 0)));
}

// The frame's mask, or its overlay, written into the output buffer's own pixels: what is
// drawn follows the negotiated output format, not the `mode` property, which may have changed
// since (its caps follow when negotiated again).
void writeOutput(const cv::Mat& frame, const movseg::Result& result, guint64 number,
                 GstVideoFrame* out) {
  cv::Mat output = matOf(out);
  const cv::Mat drawn = output.channels() == 1
                            ? result.mask
                            : movseg::drawOverlay(frame, result, "frame " + std::to_string(number));
  CV_Assert(drawn.size() == output.size() && drawn.type() == output.type());
  drawn.copyTo(output);
}

GstFlowReturn transformFrame(GstVideoFilter* filter, GstVideoFrame* in, GstVideoFrame* out) {
  bool post_messages = true;
  const cv::Mat frame = matOf(in);
  State& state = stateOf(filter);
  movseg::Result result;
  // A frame the segmenter refuses (one beyond its size limits) stops the stream with an error
  // on the bus, as `movseg segment` stops with one line; an exception must not cross into C.
  try {
    result = segmenterFor(filter, frame.size(), &post_messages)->process(frame);
    writeOutput(frame, result, state.frame, out);
  } catch (const std::exception& e) {
    GST_ELEMENT_ERROR(filter, STREAM, FAILED, ("%s", e.what()), (nullptr));
    return GST_FLOW_ERROR;
  }
  if (post_messages) {
    GstStructure* diagnostics = movseg::gst::diagnosticsStructure(
        result.diagnostics, state.frame, GST_BUFFER_PTS(in->buffer));
    gst_element_post_message(GST_ELEMENT(filter),
                             gst_message_new_element(GST_OBJECT(filter), diagnostics));
  }
  ++state.frame;
  return GST_FLOW_OK;
}

void finalize(GObject* object) {
  delete GST_MOVSEG(object)->state;
  G_OBJECT_CLASS(gst_movseg_parent_class)->finalize(object);
}

void installProperties(GObjectClass* object_class) {
  const auto flags = static_cast<GParamFlags>(G_PARAM_READWRITE | GST_PARAM_MUTABLE_PLAYING);
  g_object_class_install_property(
      object_class, kPropMode,
      g_param_spec_enum("mode", "mode",
                        "what the element outputs (changed while playing: from the next caps "
                        "negotiation downstream accepts)",
                        modeType(), static_cast<gint>(Mode::kMask), flags));
  g_object_class_install_property(
      object_class, kPropPostMessages,
      g_param_spec_boolean("post-messages", "post-messages",
                           "post each frame's diagnostics as an element message named movseg",
                           TRUE, static_cast<GParamFlags>(G_PARAM_READWRITE |
                                                          GST_PARAM_MUTABLE_PLAYING)));
  g_object_class_install_property(
      object_class, kPropIgnore,
      g_param_spec_string(
          "ignore", "ignore",
          "what is fixed to the camera (a bonnet, a timestamp), never in the mask: rectangles "
          "x,y,w,h in fractions of the frame, separated by ';' (\"0,0.8,1,0.2\": the bottom "
          "fifth); empty: none",
          "", static_cast<GParamFlags>(G_PARAM_READWRITE | GST_PARAM_MUTABLE_PLAYING)));
  movseg::gst::installParamProperties(object_class, kFirstParamProp);
}

void addPadTemplates(GstElementClass* element_class) {
  gst_element_class_add_pad_template(
      element_class,
      gst_pad_template_new("sink", GST_PAD_SINK, GST_PAD_ALWAYS,
                           gst_caps_from_string(GST_VIDEO_CAPS_MAKE(MOVSEG_INPUT_FORMATS))));
  gst_element_class_add_pad_template(
      element_class,
      gst_pad_template_new("src", GST_PAD_SRC, GST_PAD_ALWAYS,
                           gst_caps_from_string(GST_VIDEO_CAPS_MAKE("{ GRAY8, BGR }"))));
}

}  // namespace

static void gst_movseg_class_init(GstMovsegClass* klass) {
  GST_DEBUG_CATEGORY_INIT(movseg_debug, "movseg", 0, "moving object segmentation");
  auto* object_class = G_OBJECT_CLASS(klass);
  object_class->set_property = setProperty;
  object_class->get_property = getProperty;
  object_class->finalize = finalize;
  installProperties(object_class);

  auto* element_class = GST_ELEMENT_CLASS(klass);
  gst_element_class_set_static_metadata(
      element_class, "Moving object segmentation", "Filter/Analyzer/Video",
      "Segments what moves in video from a moving camera: outputs the mask or an overlay, and "
      "posts each frame's diagnostics as an element message",
      "movseg");
  addPadTemplates(element_class);

  auto* transform_class = GST_BASE_TRANSFORM_CLASS(klass);
  transform_class->start = start;
  transform_class->sink_event = sinkEvent;
  transform_class->transform_caps = transformCaps;
  GST_VIDEO_FILTER_CLASS(klass)->transform_frame = transformFrame;
}

static void gst_movseg_init(GstMovseg* self) { self->state = new State; }
