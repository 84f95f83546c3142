#include "sshsig_in_process.hpp"

#include <openssl/evp.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace acetate {
namespace {

// ---- the wire format: big-endian uint32 lengths before byte strings ----------------------

class Reader {
  public:
    explicit Reader(std::string_view bytes) : bytes_(bytes) {}
    std::optional<uint32_t> u32() {
        if (bytes_.size() < 4) return std::nullopt;
        const auto* b = reinterpret_cast<const unsigned char*>(bytes_.data());
        const uint32_t v = uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | b[3];
        bytes_.remove_prefix(4);
        return v;
    }
    std::optional<std::string_view> string() {
        const auto length = u32();
        if (!length || bytes_.size() < *length) return std::nullopt;
        const std::string_view s = bytes_.substr(0, *length);
        bytes_.remove_prefix(*length);
        return s;
    }
    std::optional<std::string_view> raw(size_t n) {
        if (bytes_.size() < n) return std::nullopt;
        const std::string_view s = bytes_.substr(0, n);
        bytes_.remove_prefix(n);
        return s;
    }
    bool done() const { return bytes_.empty(); }

  private:
    std::string_view bytes_;
};

void put_string(std::string& out, std::string_view s) {
    const uint32_t n = uint32_t(s.size());
    out += char(n >> 24);
    out += char(n >> 16);
    out += char(n >> 8);
    out += char(n);
    out += s;
}

std::optional<std::string> base64_decode(std::string_view text) {
    std::string clean;
    for (char c : text)
        if (c != '\n' && c != '\r' && c != ' ' && c != '\t') clean += c;
    if (clean.empty() || clean.size() % 4 != 0) return std::nullopt;
    std::string out(clean.size() / 4 * 3, '\0');
    const int n =
        EVP_DecodeBlock(reinterpret_cast<unsigned char*>(out.data()),
                        reinterpret_cast<const unsigned char*>(clean.data()), int(clean.size()));
    if (n < 0) return std::nullopt;
    size_t padding = 0;
    if (clean.back() == '=') ++padding;
    if (clean.size() > 1 && clean[clean.size() - 2] == '=') ++padding;
    out.resize(size_t(n) - padding);
    return out;
}

// An Ed25519 public key blob: string "ssh-ed25519", string key (32 bytes). nullopt otherwise.
std::optional<std::string_view> ed25519_key(std::string_view blob) {
    Reader r(blob);
    const auto type = r.string();
    const auto key = r.string();
    if (!type || *type != "ssh-ed25519" || !key || key->size() != 32 || !r.done())
        return std::nullopt;
    return key;
}

// ---- the text files -------------------------------------------------------------------

std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

std::vector<std::string> split(std::string_view list, char by) {
    std::vector<std::string> out;
    size_t start = 0;
    for (;;) {
        const size_t at = list.find(by, start);
        out.emplace_back(list.substr(start, at - start));
        if (at == std::string_view::npos) return out;
        start = at + 1;
    }
}

bool is_pattern(std::string_view s) {
    return s.find_first_of("*?!\"") != std::string_view::npos;
}

struct AllowedLine {
    std::vector<std::string> principals;
    std::optional<std::vector<std::string>> namespaces;  // none: every namespace
    std::string key_type, key_blob;                      // the blob decoded
};

// Every line of the file, or nullopt when a line uses anything beyond plain principals, an
// optional namespaces="..." of plain names, a key type and its base64 blob: such files are
// left to ssh-keygen.
std::optional<std::vector<AllowedLine>> parse_allowed(std::string_view text) {
    std::vector<AllowedLine> out;
    std::istringstream in{std::string(text)};
    for (std::string line; std::getline(in, line);) {
        const auto w = words(line);
        if (w.empty() || w[0][0] == '#') continue;
        if (w.size() < 3) return std::nullopt;
        AllowedLine a;
        if (is_pattern(w[0])) return std::nullopt;
        a.principals = split(w[0], ',');
        size_t next = 1;
        if (w[1].rfind("namespaces=\"", 0) == 0) {
            const std::string& option = w[1];
            // One option, quoted, of plain names: namespaces="a,b".
            if (option.size() < 13 || option.back() != '"') return std::nullopt;
            const std::string list = option.substr(12, option.size() - 13);
            if (list.find('"') != std::string::npos || is_pattern(list)) return std::nullopt;
            a.namespaces = split(list, ',');
            next = 2;
        } else if (w[1].rfind("ssh-", 0) != 0 && w[1].rfind("ecdsa-", 0) != 0 &&
                   w[1].rfind("sk-", 0) != 0) {
            return std::nullopt;  // another option (cert-authority, valid-after, ...)
        }
        if (w.size() < next + 2) return std::nullopt;
        a.key_type = w[next];
        auto blob = base64_decode(w[next + 1]);
        if (!blob) return std::nullopt;
        a.key_blob = std::move(*blob);
        out.push_back(std::move(a));
    }
    return out;
}

// The key blobs a plain list of public keys revokes; nullopt for anything else (a KRL).
std::optional<std::vector<std::string>> parse_revoked(std::string_view text) {
    std::vector<std::string> out;
    std::istringstream in{std::string(text)};
    for (std::string line; std::getline(in, line);) {
        const auto w = words(line);
        if (w.empty() || w[0][0] == '#') continue;
        if (w.size() < 2 || w[0].rfind("ssh-", 0) != 0) return std::nullopt;
        auto blob = base64_decode(w[1]);
        if (!blob) return std::nullopt;
        out.push_back(std::move(*blob));
    }
    return out;
}

// ---- the signature ----------------------------------------------------------------------

struct Signature {
    std::string public_key_blob;
    std::string_view name_space, reserved, hash;
    std::string_view signature;  // the raw 64 bytes
    std::string blob;            // owns the views above
};

std::optional<Signature> parse_signature(std::string_view armored) {
    constexpr std::string_view kBegin = "-----BEGIN SSH SIGNATURE-----";
    constexpr std::string_view kEnd = "-----END SSH SIGNATURE-----";
    const size_t begin = armored.find(kBegin);
    const size_t end = armored.find(kEnd);
    if (begin == std::string_view::npos || end == std::string_view::npos || end < begin)
        return std::nullopt;
    auto decoded =
        base64_decode(armored.substr(begin + kBegin.size(), end - begin - kBegin.size()));
    if (!decoded) return std::nullopt;
    Signature s;
    s.blob = std::move(*decoded);
    Reader r(s.blob);
    const auto magic = r.raw(6);
    const auto version = r.u32();
    const auto key = r.string();
    const auto name_space = r.string();
    const auto reserved = r.string();
    const auto hash = r.string();
    const auto signature = r.string();
    if (!magic || *magic != "SSHSIG" || !version || *version != 1 || !key || !name_space ||
        !reserved || !hash || !signature || !r.done())
        return std::nullopt;
    if (!ed25519_key(*key)) return std::nullopt;
    Reader sig(*signature);
    const auto sig_type = sig.string();
    const auto sig_bytes = sig.string();
    if (!sig_type || *sig_type != "ssh-ed25519" || !sig_bytes || sig_bytes->size() != 64 ||
        !sig.done())
        return std::nullopt;
    s.public_key_blob = std::string(*key);
    s.name_space = *name_space;
    s.reserved = *reserved;
    s.hash = *hash;
    s.signature = *sig_bytes;
    return s;
}

bool ed25519_verifies(std::string_view key, std::string_view signature, std::string_view data) {
    std::unique_ptr<EVP_PKEY, decltype(&EVP_PKEY_free)> pkey(
        EVP_PKEY_new_raw_public_key(EVP_PKEY_ED25519, nullptr,
                                    reinterpret_cast<const unsigned char*>(key.data()), key.size()),
        EVP_PKEY_free);
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx(EVP_MD_CTX_new(), EVP_MD_CTX_free);
    if (!pkey || !ctx ||
        EVP_DigestVerifyInit(ctx.get(), nullptr, nullptr, nullptr, pkey.get()) != 1)
        return false;
    return EVP_DigestVerify(ctx.get(), reinterpret_cast<const unsigned char*>(signature.data()),
                            signature.size(), reinterpret_cast<const unsigned char*>(data.data()),
                            data.size()) == 1;
}

}  // namespace

bool verified_in_process(std::string_view allowed_signers, const std::string_view* revoked_keys,
                         std::string_view principal, std::string_view name_space,
                         std::string_view message, std::string_view armored) {
    const auto allowed = parse_allowed(allowed_signers);
    if (!allowed) return false;
    const auto sig = parse_signature(armored);
    if (!sig || sig->name_space != name_space) return false;
    const EVP_MD* md = sig->hash == "sha512"   ? EVP_sha512()
                       : sig->hash == "sha256" ? EVP_sha256()
                                               : nullptr;
    if (!md) return false;

    bool listed = false;
    for (const AllowedLine& line : *allowed) {
        if (line.key_blob != sig->public_key_blob) continue;
        bool named = false;
        for (const std::string& p : line.principals) named = named || p == principal;
        bool in_namespace = !line.namespaces;
        if (line.namespaces)
            for (const std::string& n : *line.namespaces)
                in_namespace = in_namespace || n == name_space;
        listed = listed || (named && in_namespace);
    }
    if (!listed) return false;
    if (revoked_keys) {
        const auto revoked = parse_revoked(*revoked_keys);
        if (!revoked) return false;
        for (const std::string& blob : *revoked)
            if (blob == sig->public_key_blob) return false;
    }

    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int digest_size = 0;
    if (EVP_Digest(message.data(), message.size(), digest, &digest_size, md, nullptr) != 1)
        return false;
    std::string signed_data = "SSHSIG";
    put_string(signed_data, sig->name_space);
    put_string(signed_data, sig->reserved);
    put_string(signed_data, sig->hash);
    put_string(signed_data, std::string_view(reinterpret_cast<const char*>(digest), digest_size));
    return ed25519_verifies(*ed25519_key(sig->public_key_blob), sig->signature, signed_data);
}

}  // namespace acetate
