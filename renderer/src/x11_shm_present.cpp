#include "x11_shm_present.hpp"

#include <sys/ipc.h>
#include <sys/shm.h>

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>

#include "vt/core/error.hpp"

namespace vt::renderer {
namespace {

// Xlib reports protocol errors through one process-wide handler whose default exits; the checks
// below swap in one that records them for one round trip. They run when the target is made and
// at a resize (render thread); GLFW swaps in its own the same way on the main thread, so the two
// can interleave, and the handler left behind may be either's recorder rather than the default:
// a later protocol error is then dropped instead of ending the process.
int g_xError = 0;
int recordXError(Display*, XErrorEvent* e) {
  g_xError = e->error_code;
  return 0;
}

// Runs `request` and a round trip; true when the server raised no error.
template <typename Request>
bool succeeds(Display* display, Request request) {
  g_xError = 0;
  XErrorHandler previous = XSetErrorHandler(recordXError);
  request();
  XSync(display, False);
  XSetErrorHandler(previous);
  return g_xError == 0;
}

}  // namespace

struct X11ShmPresenter::State {
  Display* display = nullptr;
  Window window = 0;
  GC gc = nullptr;
  Visual* visual = nullptr;
  int depth = 0;
  XShmSegmentInfo segment{};
  XImage* image = nullptr;

  void releaseImage() noexcept {
    if (!image) return;
    XShmDetach(display, &segment);
    XSync(display, False);
    image->data = nullptr;  // the segment's, not Xlib's to free
    XDestroyImage(image);
    shmdt(segment.shmaddr);
    image = nullptr;
    segment = {};
  }
  ~State() {
    releaseImage();
    if (gc) XFreeGC(display, gc);
    if (display) XCloseDisplay(display);
  }
};

std::unique_ptr<X11ShmPresenter> X11ShmPresenter::open(unsigned long window) {
  auto state = std::make_unique<State>();
  state->display = XOpenDisplay(nullptr);
  if (!state->display) return nullptr;
  Display* d = state->display;
  int major = 0, minor = 0, opcode = 0, event = 0, error = 0;
  Bool sharedPixmaps = False;
  if (!XShmQueryVersion(d, &major, &minor, &sharedPixmaps)) return nullptr;
  if (XQueryExtension(d, "DRI3", &opcode, &event, &error)) return nullptr;
  XWindowAttributes attributes{};
  if (!succeeds(d, [&] { XGetWindowAttributes(d, window, &attributes); })) return nullptr;
  const Visual* v = attributes.visual;
  if (attributes.depth != 24 || !v || v->red_mask != 0xff0000 || v->green_mask != 0xff00 || v->blue_mask != 0xff)
    return nullptr;
  state->window = window;
  state->visual = attributes.visual;
  state->depth = attributes.depth;
  state->gc = XCreateGC(d, window, 0, nullptr);
  // A server that cannot map this process's segments (another machine) refuses the attach.
  auto presenter = std::unique_ptr<X11ShmPresenter>(new X11ShmPresenter(std::move(state)));
  try {
    presenter->pixels(1, 1);
  } catch (const Error&) {
    return nullptr;
  }
  return presenter;
}

X11ShmPresenter::X11ShmPresenter(std::unique_ptr<State> state) : m_state(std::move(state)) {}

X11ShmPresenter::~X11ShmPresenter() = default;

std::uint8_t* X11ShmPresenter::pixels(std::uint32_t width, std::uint32_t height) {
  State& s = *m_state;
  if (s.image && std::uint32_t(s.image->width) == width && std::uint32_t(s.image->height) == height)
    return reinterpret_cast<std::uint8_t*>(s.image->data);
  s.releaseImage();
  XImage* image = XShmCreateImage(s.display, s.visual, unsigned(s.depth), ZPixmap, nullptr, &s.segment, width, height);
  if (!image) fail("window: cannot make a ", width, "x", height, " shared-memory image");
  if (image->bits_per_pixel != 32 || std::uint32_t(image->bytes_per_line) != width * 4) {
    const int bits = image->bits_per_pixel;
    XDestroyImage(image);
    fail("window: the X server's shared-memory image has ", bits, " bits per pixel, not 32");
  }
  s.segment.shmid = shmget(IPC_PRIVATE, std::size_t(image->bytes_per_line) * height, IPC_CREAT | 0600);
  if (s.segment.shmid < 0) {
    XDestroyImage(image);
    fail("window: cannot make a shared-memory segment for a ", width, "x", height, " frame");
  }
  s.segment.shmaddr = static_cast<char*>(shmat(s.segment.shmid, nullptr, 0));
  shmctl(s.segment.shmid, IPC_RMID, nullptr);  // freed once both sides detach
  if (s.segment.shmaddr == reinterpret_cast<char*>(-1)) {
    XDestroyImage(image);
    fail("window: cannot map the frame's shared-memory segment");
  }
  s.segment.readOnly = True;
  image->data = s.segment.shmaddr;
  s.image = image;
  if (!succeeds(s.display, [&] { XShmAttach(s.display, &s.segment); })) {
    image->data = nullptr;
    XDestroyImage(image);
    shmdt(s.segment.shmaddr);
    s.image = nullptr;
    fail("window: the X server cannot attach this process's shared memory (a remote display?)");
  }
  return reinterpret_cast<std::uint8_t*>(s.image->data);
}

void X11ShmPresenter::put() {
  State& s = *m_state;
  XShmPutImage(s.display, s.window, s.gc, s.image, 0, 0, 0, 0, unsigned(s.image->width), unsigned(s.image->height), False);
  XSync(s.display, False);
}

}  // namespace vt::renderer
