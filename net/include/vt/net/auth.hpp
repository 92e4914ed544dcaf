#pragma once
// Authenticated sessions (docs/protocol.md "Authentication"): a 32-byte shared key, handshake
// datagrams sealed with it under a random 24-byte nonce, stream datagrams sealed with
// per-session, per-direction keys derived from the shared key and both handshake nonces, under
// a nonce built from the session id, the direction and the datagram sequence (no nonce bytes
// on the wire). XChaCha20-Poly1305 from libsodium; a 64-datagram replay window. Sealing and
// opening are allocation-free and noexcept (network threads); key files and text throw.
#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace vt::net {

inline constexpr std::size_t kKeySize = 32;
inline constexpr std::size_t kNonceSize = 24;
inline constexpr std::size_t kTagSize = 16;

/// The shared secret of a client and its server.
using Key = std::array<std::uint8_t, kKeySize>;

/// Which way a stream datagram travels (its key and nonce space).
enum class Direction : std::uint8_t { ClientToServer = 1, ServerToClient = 2 };

/// The two stream keys of one session.
struct SessionKeys {
  Key clientToServer{};
  Key serverToClient{};
  const Key& of(Direction d) const noexcept { return d == Direction::ClientToServer ? clientToServer : serverToClient; }
};

/// A new random key (libsodium's CSPRNG). Throws vt::Error when libsodium cannot start.
Key generateKey();
/// 64 lowercase hex digits.
std::string keyToHex(const Key& key);
/// Parses 64 hex digits (surrounding whitespace ignored); throws vt::Error naming `what`.
Key parseKeyHex(std::string_view text, std::string_view what);
/// Reads a key file (64 hex digits); throws vt::Error naming the file and the problem.
Key readKeyFile(const std::filesystem::path& path);
/// Writes `key` as hex to a new file readable by its owner only; throws naming the file.
void writeKeyFile(const std::filesystem::path& path, const Key& key);
/// `--key FILE|HEX` of the client: 64 hex digits, else a key file.
Key keyFromArgument(std::string_view text);

/// Fills `out` with random bytes. Any thread.
void randomBytes(std::span<std::uint8_t> out) noexcept;

/// The stream keys of the session that `helloNonce`/`acceptNonce` opened under `key`.
SessionKeys deriveSessionKeys(const Key& key, std::uint32_t sessionId,
                              const std::array<std::uint8_t, kNonceSize>& helloNonce,
                              const std::array<std::uint8_t, kNonceSize>& acceptNonce) noexcept;

/// The stream nonce of datagram `sequence` of `sessionId` going `direction`.
std::array<std::uint8_t, kNonceSize> streamNonce(std::uint32_t sessionId, Direction direction,
                                                 std::uint64_t sequence) noexcept;

/// Encrypts `text` in place and writes its tag; `ad` is authenticated too. Any thread.
void seal(const Key& key, const std::array<std::uint8_t, kNonceSize>& nonce, std::span<const std::uint8_t> ad,
          std::span<std::uint8_t> text, std::span<std::uint8_t, kTagSize> tag) noexcept;
/// Checks the tag and decrypts `text` in place; false (text unspecified) when forged. Any thread.
bool open(const Key& key, const std::array<std::uint8_t, kNonceSize>& nonce, std::span<const std::uint8_t> ad,
          std::span<std::uint8_t> text, std::span<const std::uint8_t, kTagSize> tag) noexcept;

/// A 16-byte digest (BLAKE2b) of `bytes` under `key`: a server's challenge cookie over the
/// client's address and the time, and its record of the hellos it has seen. Any thread.
std::array<std::uint8_t, 16> digest16(const Key& key, std::span<const std::uint8_t> bytes) noexcept;

/// Throws vt::Error naming `what` when `key` cannot be a random key: all zeros, fewer than 16
/// distinct byte values (a random key has ~30), or bytes that count up or down by a step.
void checkKeyStrength(const Key& key, std::string_view what);

/// Sliding window over received sequence numbers (the newest 64): a datagram is taken once.
class ReplayWindow {
 public:
  /// True when `sequence` was not received yet and is not older than the window. Any thread
  /// that owns the window.
  bool fresh(std::uint64_t sequence) const noexcept;
  /// Records `sequence` as received (after it authenticated).
  void accept(std::uint64_t sequence) noexcept;
  /// The newest sequence received (0 before any).
  std::uint64_t newest() const noexcept { return m_newest; }
  void reset() noexcept { m_newest = 0, m_bits = 0; }

 private:
  std::uint64_t m_newest = 0;
  std::uint64_t m_bits = 0;  // bit i: newest - i received
};

}  // namespace vt::net
