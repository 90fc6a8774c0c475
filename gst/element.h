// The GStreamer element movseg, a GstVideoFilter: raw video in (BGR, BGRx or GRAY8), out the
// mask of what moves (GRAY8, 0 / 255) or the overlay (BGR), one movseg::Segmenter per stream.
// Its properties are movseg's parameters (properties.h) plus `mode`, `post-messages` and
// `ignore`; each frame's diagnostics go to the bus as an element message named "movseg".
#pragma once

#include <gst/video/gstvideofilter.h>

G_BEGIN_DECLS

#define GST_TYPE_MOVSEG (gst_movseg_get_type())
G_DECLARE_FINAL_TYPE(GstMovseg, gst_movseg, GST, MOVSEG, GstVideoFilter)

G_END_DECLS
