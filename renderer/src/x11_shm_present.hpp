#pragma once
// Frames put into an X11 window through MIT-SHM, on an X connection of its own (internal; the
// window target's host present). For software devices on X servers without DRI3 (Xvfb, VNC
// servers), where Mesa 22.3's own present sends each frame through the X socket in 219 KB writes
// whose duration swings with the server's scheduling (docs/renderer.md, "Presenting").
#include <cstdint>
#include <memory>

namespace vt::renderer {

class X11ShmPresenter {
 public:
  /// A presenter for the X window `window` of the display named by $DISPLAY, or nullptr when
  /// there is none, the server lacks MIT-SHM or cannot attach this process's segments (a remote
  /// display), has DRI3 (Mesa presents through shared memory itself there), or the window's
  /// pixels are not 32-bit B G R X.
  static std::unique_ptr<X11ShmPresenter> open(unsigned long window);
  ~X11ShmPresenter();
  X11ShmPresenter(const X11ShmPresenter&) = delete;
  X11ShmPresenter& operator=(const X11ShmPresenter&) = delete;

  /// The next frame's pixels (rows of width * 4 bytes, B G R X), reallocated when the size
  /// changes. Throws vt::Error when the shared segment cannot be made or attached.
  std::uint8_t* pixels(std::uint32_t width, std::uint32_t height);
  /// Puts the frame into the window and returns once the server has copied it (a round trip):
  /// the moment the frame is on this server's screen.
  void put();

 private:
  struct State;
  explicit X11ShmPresenter(std::unique_ptr<State> state);
  std::unique_ptr<State> m_state;
};

}  // namespace vt::renderer
