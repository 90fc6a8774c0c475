#include "live_window.h"

#include <netdb.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

#include <opencv2/highgui.hpp>

namespace movseg::cli {
namespace {

constexpr const char* kWindowName = "movseg";

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value != nullptr ? value : "";
}

bool accepts(int family, const sockaddr* address, socklen_t length) {
  const int fd = socket(family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  if (fd < 0) return false;
  const bool connected = connect(fd, address, length) == 0;
  close(fd);
  return connected;
}

// A local socket by path, or in Linux's abstract namespace (where X servers also listen).
bool unixSocketAccepts(const std::string& path, bool abstract) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  const size_t offset = abstract ? 1 : 0;
  if (path.empty() || path.size() + offset >= sizeof address.sun_path) return false;
  std::memcpy(address.sun_path + offset, path.data(), path.size());
  const auto length =
      static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + offset + path.size());
  return accepts(AF_UNIX, reinterpret_cast<const sockaddr*>(&address), length);
}

bool tcpAccepts(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0) return false;
  bool connected = false;
  for (const addrinfo* a = found; a != nullptr && !connected; a = a->ai_next) {
    connected = accepts(a->ai_family, a->ai_addr, a->ai_addrlen);
  }
  freeaddrinfo(found);
  return connected;
}

// DISPLAY is [host]:number[.screen]: a local socket, or TCP port 6000 + number (ssh -X).
bool x11DisplayAccepts(const std::string& display) {
  const size_t colon = display.rfind(':');
  if (colon == std::string::npos) return false;
  const std::string host = display.substr(0, colon);
  const int number = std::atoi(display.c_str() + colon + 1);
  if (!host.empty() && host != "unix") return tcpAccepts(host, 6000 + number);
  const std::string path = "/tmp/.X11-unix/X" + std::to_string(number);
  return unixSocketAccepts(path, false) || unixSocketAccepts(path, true);
}

bool waylandDisplayAccepts(const std::string& display) {
  if (display.empty() || display[0] == '/') return unixSocketAccepts(display, false);
  return unixSocketAccepts(environment("XDG_RUNTIME_DIR") + "/" + display, false);
}

// Asked of the display's socket rather than of HighGUI, whose Qt backend aborts the process
// when it cannot connect.
bool hasDisplay() {
  const std::string x11 = environment("DISPLAY"), wayland = environment("WAYLAND_DISPLAY");
  return (!x11.empty() && x11DisplayAccepts(x11)) ||
         (!wayland.empty() && waylandDisplayAccepts(wayland));
}

}  // namespace

LiveWindow::LiveWindow(bool enabled) : enabled_(enabled) {
  if (!enabled_) return;
  if (!hasDisplay()) throw std::runtime_error("--show needs a display; none found");
  cv::namedWindow(kWindowName, cv::WINDOW_AUTOSIZE);
}

LiveWindow::~LiveWindow() {
  if (enabled_) cv::destroyWindow(kWindowName);
}

bool LiveWindow::show(const cv::Mat& picture) {
  if (!enabled_) return true;
  cv::imshow(kWindowName, picture);
  const int key = cv::waitKey(1);
  return key != 'q' && key != 27 && cv::getWindowProperty(kWindowName, cv::WND_PROP_VISIBLE) > 0;
}

}  // namespace movseg::cli
