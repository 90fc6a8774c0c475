// The plugin that holds the element movseg (element.h).
#include <gst/gst.h>

#include "element.h"

namespace {

gboolean pluginInit(GstPlugin* plugin) {
  return gst_element_register(plugin, "movseg", GST_RANK_NONE, GST_TYPE_MOVSEG);
}

}  // namespace

GST_PLUGIN_DEFINE(GST_VERSION_MAJOR, GST_VERSION_MINOR, movseg,
                  "Moving object segmentation for freely moving cameras", pluginInit,
                  MOVSEG_VERSION, GST_LICENSE_UNKNOWN, "movseg", "the movseg repository")
