// The element's properties and messages, generated from movseg's field tables: a property per
// field of movseg/params.def (named with '-': lk-window, motion-model), of the field's type,
// range and default, documented by its help text; a message structure per frame with every
// field of movseg/diagnostics.def under its name. A new parameter or diagnostic appears here
// with no edit.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <gst/gst.h>
#include <opencv2/core.hpp>

#include "movseg/params.h"
#include "movseg/segmenter.h"

namespace movseg::gst {

// Installs one property per field of paramFields(), the i-th with id first_id + i.
void installParamProperties(GObjectClass* klass, guint first_id);

// Sets the i-th field of paramFields() from a property value. Throws std::invalid_argument
// naming the parameter when the value is not one the field takes (an even window side).
void setParamProperty(Params* params, std::size_t field, const GValue* value);

// The i-th field of paramFields() as a property value.
void getParamProperty(const Params& params, std::size_t field, GValue* value);

// The `ignore` property's text: rectangles "x,y,w,h" in fractions of the frame's width and
// height, separated by ';' ("0,0.8,1,0.2; 0.85,0,0.15,0.06": a bonnet and a timestamp), so that
// a region fixed to the camera needs no image file, and fits any frame size; "" is none. Throws
// std::invalid_argument naming the property when the text is not such a list.
std::vector<cv::Rect2d> parseIgnoredRectangles(const std::string& text);

// Those rectangles as Segmenter::setIgnoredRegion takes them, at `size`: 255 inside, edges
// rounded to the nearest pixel; empty when there are none.
cv::Mat ignoredRegion(const std::vector<cv::Rect2d>& rectangles, cv::Size size);

// The structure of an element message: "movseg", the frame's number and timestamp (none for a
// buffer without one), then every diagnostic (booleans, ints, doubles; the camera model as an
// array of its 9 entries, row by row).
GstStructure* diagnosticsStructure(const Diagnostics& diagnostics, guint64 frame,
                                   GstClockTime timestamp);

}  // namespace movseg::gst
