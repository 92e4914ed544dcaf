#include "vt/net/auth.hpp"

#include <sodium.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <optional>
#include <set>
#include <system_error>

#include "vt/core/error.hpp"
#include "vt/core/file_io.hpp"
#include "vt/core/output_file.hpp"
#include "vt/core/text_input.hpp"

namespace vt::net {

namespace {

void initSodium() {
  // sodium_init is idempotent and thread-safe; < 0 means no usable entropy source.
  if (sodium_init() < 0) fail("libsodium could not start (no random source)");
}

// Starts libsodium before main: seal/open and randomBytes then never need to (noexcept paths).
const bool g_sodiumReady = [] {
  try {
    initSodium();
    return true;
  } catch (const Error&) {
    return false;
  }
}();

int hexValue(char c) noexcept {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string_view trim(std::string_view text) noexcept {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front()))) text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.remove_suffix(1);
  return text;
}

}  // namespace

Key generateKey() {
  initSodium();
  Key key;
  crypto_aead_xchacha20poly1305_ietf_keygen(key.data());
  return key;
}

std::string keyToHex(const Key& key) {
  std::string hex(kKeySize * 2, '0');
  static constexpr char kDigits[] = "0123456789abcdef";
  for (std::size_t i = 0; i < kKeySize; ++i) {
    hex[2 * i] = kDigits[key[i] >> 4];
    hex[2 * i + 1] = kDigits[key[i] & 15];
  }
  return hex;
}

Key parseKeyHex(std::string_view text, std::string_view what) {
  text = trim(text);
  if (text.size() != kKeySize * 2) fail(what, ": a key is ", kKeySize * 2, " hex digits, got ", text.size(), " characters");
  Key key;
  for (std::size_t i = 0; i < kKeySize; ++i) {
    const int hi = hexValue(text[2 * i]), lo = hexValue(text[2 * i + 1]);
    if (hi < 0 || lo < 0) fail(what, ": character ", 2 * i + (hi < 0 ? 1 : 2), " of the key is not a hex digit");
    key[i] = std::uint8_t(hi << 4 | lo);
  }
  checkKeyStrength(key, what);
  return key;
}

void checkKeyStrength(const Key& key, std::string_view what) {
  const std::set<std::uint8_t> distinct(key.begin(), key.end());
  bool counting = true;  // 00 01 02 ..., or any constant step
  for (std::size_t i = 2; i < key.size(); ++i) counting = counting && std::uint8_t(key[i] - key[i - 1]) == std::uint8_t(key[1] - key[0]);
  const char* why = distinct.size() == 1 && key[0] == 0 ? "is all zeros"
                    : counting                           ? "counts by a constant step"
                    : distinct.size() < 16               ? "repeats a few byte values"
                                                         : nullptr;
  if (why) {
    fail(what, ": the key ", why, ", so it is not a random key and protects nothing; make one with "
               "`vtouching serve --key NEWFILE` (it writes a random key there)");
  }
}

Key readKeyFile(const std::filesystem::path& path) {
  const std::string what = "key file '" + path.string() + "'";
  checkInputFile(path, "key file", 4096);  // names a folder, a loop, a missing file, ...
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw Error(str("key file ", describeErrno(path, "read", errno)));
  // As ssh refuses a private key others can read: a shared secret anyone here can read is none.
  if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", unsigned(st.st_mode & 07777));
    fail(what, ": its permissions ", mode, " let other users read or change the key; make it private with `chmod 600 ",
         path.string(), "`");
  }
  if (st.st_uid != ::geteuid()) {
    fail(what, ": owned by another user (uid ", st.st_uid, "); a key file must belong to the user running vtouching");
  }
  return parseKeyHex(readInputText(path, "key file", 4096), what);
}

void writeKeyFile(const std::filesystem::path& path, const Key& key) {
  std::error_code ec;
  if (std::filesystem::exists(std::filesystem::symlink_status(path, ec)))
    fail("key file ", path.string(), ": already exists (a key is never overwritten)");
  // Owner-only from the start (never world-readable, not even briefly), whole or absent: a full
  // disk leaves no truncated key that later runs would refuse to replace.
  const mode_t old = ::umask(077);
  std::optional<OutputFile> file;
  try {
    file.emplace(path);
  } catch (...) {
    ::umask(old);
    throw;
  }
  ::umask(old);
  file->write(keyToHex(key) + "\n");
  file->commit();
}

Key keyFromArgument(std::string_view text) {
  const std::string_view trimmed = trim(text);
  std::error_code ec;
  const bool isFile = std::filesystem::symlink_status(std::string(text), ec).type() != std::filesystem::file_type::not_found;
  if (trimmed.size() == kKeySize * 2 && !isFile) return parseKeyHex(trimmed, "--key");
  if (isFile) return readKeyFile(std::string(text));
  // Neither: say which it looked like (a short hex string is a cut key, not a file name).
  const bool hex = !trimmed.empty() && std::all_of(trimmed.begin(), trimmed.end(), [](char c) { return hexValue(c) >= 0; });
  if (hex) {
    fail("--key '", text, "': not a key (a key is ", kKeySize * 2, " hex digits, this has ", trimmed.size(),
         ") and no file of that name exists");
  }
  fail("--key '", text, "': no such key file (give the server's key file, or its ", kKeySize * 2, " hex digits)");
}

void randomBytes(std::span<std::uint8_t> out) noexcept { randombytes_buf(out.data(), out.size()); }

std::array<std::uint8_t, 16> digest16(const Key& key, std::span<const std::uint8_t> bytes) noexcept {
  std::array<std::uint8_t, 16> out{};
  crypto_generichash(out.data(), out.size(), bytes.data(), bytes.size(), key.data(), key.size());
  return out;
}

SessionKeys deriveSessionKeys(const Key& key, std::uint32_t sessionId, const std::array<std::uint8_t, kNonceSize>& helloNonce,
                              const std::array<std::uint8_t, kNonceSize>& acceptNonce) noexcept {
  // BLAKE2b keyed with the shared key over both random nonces: fresh keys for every session,
  // so stream nonces (built from sequence numbers) never repeat under one key.
  std::array<std::uint8_t, 8 + 4 + 2 * kNonceSize> input{'V', 'T', 'N', 'P', '3', 's', 'e', 's'};
  for (int i = 0; i < 4; ++i) input[8 + std::size_t(i)] = std::uint8_t(sessionId >> (8 * i));
  std::copy(helloNonce.begin(), helloNonce.end(), input.begin() + 12);
  std::copy(acceptNonce.begin(), acceptNonce.end(), input.begin() + 12 + kNonceSize);
  std::array<std::uint8_t, 2 * kKeySize> out{};
  crypto_generichash(out.data(), out.size(), input.data(), input.size(), key.data(), key.size());
  SessionKeys keys;
  std::copy_n(out.begin(), kKeySize, keys.clientToServer.begin());
  std::copy_n(out.begin() + kKeySize, kKeySize, keys.serverToClient.begin());
  sodium_memzero(out.data(), out.size());
  return keys;
}

std::array<std::uint8_t, kNonceSize> streamNonce(std::uint32_t sessionId, Direction direction,
                                                 std::uint64_t sequence) noexcept {
  std::array<std::uint8_t, kNonceSize> nonce{};
  nonce[0] = std::uint8_t(direction);
  for (int i = 0; i < 4; ++i) nonce[1 + std::size_t(i)] = std::uint8_t(sessionId >> (8 * i));
  for (int i = 0; i < 8; ++i) nonce[5 + std::size_t(i)] = std::uint8_t(sequence >> (8 * i));
  return nonce;
}

void seal(const Key& key, const std::array<std::uint8_t, kNonceSize>& nonce, std::span<const std::uint8_t> ad,
          std::span<std::uint8_t> text, std::span<std::uint8_t, kTagSize> tag) noexcept {
  crypto_aead_xchacha20poly1305_ietf_encrypt_detached(text.data(), tag.data(), nullptr, text.data(), text.size(),
                                                      ad.data(), ad.size(), nullptr, nonce.data(), key.data());
}

bool open(const Key& key, const std::array<std::uint8_t, kNonceSize>& nonce, std::span<const std::uint8_t> ad,
          std::span<std::uint8_t> text, std::span<const std::uint8_t, kTagSize> tag) noexcept {
  return crypto_aead_xchacha20poly1305_ietf_decrypt_detached(text.data(), nullptr, text.data(), text.size(), tag.data(),
                                                             ad.data(), ad.size(), nonce.data(), key.data()) == 0;
}

bool ReplayWindow::fresh(std::uint64_t sequence) const noexcept {
  if (sequence == 0) return false;
  if (sequence > m_newest) return true;
  const std::uint64_t age = m_newest - sequence;
  return age < 64 && (m_bits >> age & 1) == 0;
}

void ReplayWindow::accept(std::uint64_t sequence) noexcept {
  if (sequence > m_newest) {
    const std::uint64_t shift = sequence - m_newest;
    m_bits = shift >= 64 ? 0 : m_bits << shift;
    m_bits |= 1;
    m_newest = sequence;
  } else if (m_newest - sequence < 64) {
    m_bits |= std::uint64_t(1) << (m_newest - sequence);
  }
}

}  // namespace vt::net
