#include "ssh_signature.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <fnmatch.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fstream>
#include <sstream>
#include <thread>
#include <vector>

#include "core/child_process.hpp"
#include "core/input_file.hpp"
#include "sshsig_in_process.hpp"

extern char** environ;

namespace acetate {
namespace {

namespace fs = std::filesystem;

// A private folder removed at the end of the scope: the message and the signature live there
// while ssh-keygen reads them.
class ScratchFolder {
  public:
    ScratchFolder() {
        std::string name = (fs::temp_directory_path() / "acetate-sign-XXXXXX").string();
        if (mkdtemp(name.data())) path_ = name;
    }
    ~ScratchFolder() {
        std::error_code ec;
        if (!path_.empty()) fs::remove_all(path_, ec);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const fs::path& path() const { return path_; }

  private:
    fs::path path_;
};

struct ToolRun {
    int status = -1;  // exit status; -1 when it could not start or was killed
    std::string out, err;
};

bool write_text(const fs::path& file, std::string_view text) {
    std::ofstream out(file, std::ios::binary);
    out.write(text.data(), std::streamsize(text.size()));
    return bool(out.flush());
}

std::string read_text(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

// Runs ssh-keygen with `args`, its standard input from `input`, its output in the scratch
// folder. Io when it cannot start (not installed).
Result<ToolRun> ssh_keygen(const std::vector<std::string>& args, const fs::path& input,
                           const fs::path& scratch) {
    const fs::path output = scratch / "ssh-keygen.out";
    const fs::path errors = scratch / "ssh-keygen.err";
    std::vector<std::string> argv_text = {"ssh-keygen"};
    argv_text.insert(argv_text.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_text) argv.push_back(a.data());
    argv.push_back(nullptr);

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 0, input.c_str(), O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&actions, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    posix_spawn_file_actions_addopen(&actions, 2, errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                     0600);
    pid_t pid = 0;
    const int spawned = posix_spawnp(&pid, "ssh-keygen", &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (spawned != 0)
        return make_error(ErrorCode::Io,
                          fmt::format("cannot run ssh-keygen ({}): signatures need OpenSSH's "
                                      "ssh-keygen (Debian: openssh-client)",
                                      std::strerror(spawned)));
    // A time limit, so nothing on the trust path can hang a host or the harness: a key on a
    // stalled network mount, an agent that never answers. Signing and verifying take
    // milliseconds; a passphrase typed at the prompt is allowed a minute.
    const auto deadline = std::chrono::steady_clock::now() + kSshKeygenTimeLimit;
    int wait_status = 0;
    for (;;) {
        const pid_t done = waitpid(pid, &wait_status, WNOHANG);
        if (done == pid) break;
        if (done < 0 && errno != EINTR)
            return make_error(ErrorCode::Io, "lost the ssh-keygen child process");
        if (std::chrono::steady_clock::now() > deadline) {
            ::kill(pid, SIGKILL);
            while (waitpid(pid, &wait_status, 0) < 0 && errno == EINTR) {
            }
            return make_error(ErrorCode::Io,
                              fmt::format("ssh-keygen did not finish within {} s; stopped",
                                          kSshKeygenTimeLimit.count()));
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    ToolRun run;
    run.status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
    run.out = read_text(output);
    run.err = read_text(errors);
    return run;
}

// A trust file (a key, the allowed signers, the revocations) read with the checks every input
// gets (a regular file, of bounded size, opened without blocking), then handed to ssh-keygen
// as a private copy: ssh-keygen reads exactly the bytes checked, and a FIFO or a device in
// the file's place is refused in one line instead of hanging or reading as empty.
Result<fs::path> private_copy(const fs::path& file, std::uint64_t max_bytes, std::string_view what,
                              const fs::path& scratch, const std::string& name) {
    auto bytes = read_input_file(file, max_bytes, what);
    if (!bytes) return bytes.error();
    const fs::path copy = scratch / name;
    // Owner-only: ssh-keygen refuses a private key others can read.
    const int fd = ::open(copy.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0)
        return make_error(ErrorCode::Io,
                          fmt::format("{}: cannot copy: {}", copy.string(), std::strerror(errno)));
    const bool written = ::write(fd, bytes->data(), bytes->size()) == ssize_t(bytes->size());
    if (::close(fd) != 0 || !written)
        return make_error(ErrorCode::Io, fmt::format("{}: cannot copy", copy.string()));
    return copy;
}

Result<void> invalid(std::string message) {
    return make_error(ErrorCode::InvalidInput, std::move(message));
}

}  // namespace

Result<std::string> ssh_sign(const fs::path& key, std::string_view message,
                             const char* name_space) {
    ScratchFolder scratch;
    if (scratch.path().empty())
        return make_error(ErrorCode::Io, "cannot create a temporary folder to sign in");
    const fs::path input = scratch.path() / "statement";
    if (!write_text(input, message))
        return make_error(ErrorCode::Io, fmt::format("{}: cannot write", input.string()));
    // ssh-keygen finds a public key's agent-held private half by the file's content, so a copy
    // serves both kinds of key file.
    auto key_copy = private_copy(key, kMaxKeyFileBytes, "a key file", scratch.path(), "key");
    if (!key_copy) return key_copy.error();
    // With no file named, ssh-keygen signs its standard input and writes the signature to its
    // standard output.
    auto run = ssh_keygen({"-q", "-Y", "sign", "-f", key_copy->string(), "-n", name_space}, input,
                          scratch.path());
    if (!run) return run.error();
    const std::string begin = "-----BEGIN SSH SIGNATURE-----";
    const std::string end = "-----END SSH SIGNATURE-----";
    const size_t from = run->out.find(begin);
    const size_t to = run->out.find(end);
    if (run->status != 0 || from == std::string::npos || to == std::string::npos)
        return make_error(ErrorCode::Io,
                          fmt::format("{}: cannot sign with this key: ssh-keygen: {}", key.string(),
                                      last_line(run->err)));
    return run->out.substr(from, to + end.size() - from) + "\n";
}

SignatureVerifier::SignatureVerifier(fs::path allowed_signers, const char* name_space)
    : allowed_signers_(std::move(allowed_signers)), name_space_(name_space) {}

fs::path SignatureVerifier::revoked_keys() const {
    return allowed_signers_.parent_path() / "revoked_keys";
}

fs::path SignatureVerifier::author_scopes() const {
    return allowed_signers_.parent_path() / "author_scopes";
}

Result<AuthorScopes> SignatureVerifier::read_author_scopes() const {
    auto text =
        read_input_file_if_exists(author_scopes(), kMaxTrustFileBytes, "an author-scopes file");
    if (!text) return text.error();
    if (!text->has_value()) return AuthorScopes();
    return AuthorScopes::parse(**text, author_scopes().string());
}

Result<AuthorScopes> AuthorScopes::parse(std::string_view text, std::string_view name) {
    AuthorScopes scopes;
    std::istringstream in{std::string(text)};
    size_t number = 0;
    for (std::string line; std::getline(in, line);) {
        ++number;
        std::istringstream words(line);
        std::string principal, patterns, extra;
        words >> principal >> patterns >> extra;
        if (principal.empty() || principal[0] == '#') continue;
        if (patterns.empty() || !extra.empty())
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("{}: line {}: expected a principal and its plugin id "
                                          "patterns (\"alice@example.org com.example.*\")",
                                          name, number));
        if (scopes.patterns_.count(principal))
            return make_error(
                ErrorCode::InvalidInput,
                fmt::format("{}: line {}: {} is listed twice", name, number, principal));
        auto& list = scopes.patterns_[principal];
        for (size_t at = 0; at <= patterns.size();) {
            const size_t comma = std::min(patterns.find(',', at), patterns.size());
            if (comma > at) list.push_back(patterns.substr(at, comma - at));
            at = comma + 1;
        }
    }
    return scopes;
}

bool AuthorScopes::is_author(std::string_view principal) const {
    return patterns_.find(principal) != patterns_.end();
}

bool AuthorScopes::covers(std::string_view principal, std::string_view plugin_id) const {
    const auto found = patterns_.find(principal);
    if (found == patterns_.end()) return false;
    const std::string id(plugin_id);
    for (const std::string& pattern : found->second)
        if (::fnmatch(pattern.c_str(), id.c_str(), 0) == 0) return true;
    return false;
}

std::string AuthorScopes::patterns_of(std::string_view principal) const {
    const auto found = patterns_.find(principal);
    return found == patterns_.end() ? std::string()
                                    : fmt::format("{}", fmt::join(found->second, ", "));
}

Result<void> SignatureVerifier::verify(std::string_view principal, std::string_view message,
                                       std::string_view signature) const {
    if (signature.empty()) return invalid("is missing (the sign-off is not signed)");
    // Refused before ssh-keygen reads it: a signature is a few hundred bytes, and ssh-keygen
    // takes minutes over a forged one of megabytes.
    if (signature.size() > kMaxSignatureBytes)
        return invalid(fmt::format("is {}, over the {} limit for a signature",
                                   describe_byte_count(signature.size()),
                                   describe_byte_count(kMaxSignatureBytes)));
    auto cannot_check = [](const Error& e) {
        return make_error(ErrorCode::Io, "cannot be checked: " + e.message);
    };
    auto allowed_bytes =
        read_input_file(allowed_signers_, kMaxTrustFileBytes, "an allowed-signers file");
    if (!allowed_bytes && allowed_bytes.error().code == ErrorCode::FileNotFound)
        return make_error(ErrorCode::Io, fmt::format("cannot be checked: {}: no such file (the "
                                                     "allowed signers)",
                                                     allowed_signers_.string()));
    if (!allowed_bytes) return cannot_check(allowed_bytes.error());
    // Revocations that cannot be read stop the check: ignoring them would switch revocation
    // off for whoever can put a FIFO, a folder or a device in their place.
    auto revoked_bytes =
        read_input_file_if_exists(revoked_keys(), kMaxTrustFileBytes, "a revoked-keys file");
    if (!revoked_bytes) return cannot_check(revoked_bytes.error());
    const bool has_revocations = revoked_bytes->has_value();
    // The common case is decided in this process; anything else, and every refusal with its
    // reason, by ssh-keygen itself, given private copies of exactly the bytes read above.
    const std::string_view revoked_view =
        has_revocations ? std::string_view(**revoked_bytes) : std::string_view();
    if (in_process_ &&
        verified_in_process(allowed_bytes.value(), has_revocations ? &revoked_view : nullptr,
                            principal, name_space_, message, signature))
        return {};

    ScratchFolder scratch;
    if (scratch.path().empty())
        return make_error(ErrorCode::Io, "cannot create a temporary folder to verify in");
    const fs::path allowed = scratch.path() / "allowed_signers";
    const fs::path revoked = scratch.path() / "revoked_keys";
    if (!write_text(allowed, allowed_bytes.value()) ||
        (has_revocations && !write_text(revoked, **revoked_bytes)))
        return make_error(ErrorCode::Io, "cannot write a temporary file to verify");
    const fs::path input = scratch.path() / "statement";
    const fs::path sig = scratch.path() / "statement.sig";
    if (!write_text(input, message) || !write_text(sig, signature))
        return make_error(ErrorCode::Io, "cannot write a temporary file to verify");

    std::vector<std::string> args = {
        "-Y", "verify",    "-f", allowed.string(), "-I", std::string(principal),
        "-n", name_space_, "-s", sig.string()};
    if (has_revocations) {
        args.push_back("-r");
        args.push_back(revoked.string());
    }
    auto run = ssh_keygen(args, input, scratch.path());
    if (!run) return run.error();
    if (run->status == 0) return {};

    // Why, in the maintainer's terms: ssh-keygen says only "Could not verify signature".
    const fs::path empty = scratch.path() / "empty";
    write_text(empty, "");
    auto principals =
        ssh_keygen({"-Y", "find-principals", "-f", allowed.string(), "-s", sig.string()}, empty,
                   scratch.path());
    if (!principals) return principals.error();
    if (principals->status != 0) {
        if (principals->err.find("parse") != std::string::npos ||
            principals->err.find("armor") != std::string::npos)
            return invalid(fmt::format("is not an SSH signature (ssh-keygen: {})",
                                       last_line(principals->err)));
        return invalid(fmt::format("was made by a key that {} does not list",
                                   allowed_signers_.filename().string()));
    }
    std::istringstream listed(principals->out);
    std::string name;
    bool allowed_for_principal = false;
    std::vector<std::string> names;
    while (std::getline(listed, name))
        for (size_t at = 0; at <= name.size();) {
            const size_t comma = std::min(name.find(',', at), name.size());
            const std::string one = name.substr(at, comma - at);
            if (!one.empty()) {
                names.push_back(one);
                if (one == principal) allowed_for_principal = true;
            }
            at = comma + 1;
        }
    if (!allowed_for_principal)
        return invalid(
            fmt::format("was made by {}'s key, not by {}", fmt::join(names, ", "), principal));
    if (has_revocations) {
        args.resize(args.size() - 2);
        auto unrevoked = ssh_keygen(args, input, scratch.path());
        if (unrevoked && unrevoked->status == 0)
            return invalid(
                fmt::format("was made by a revoked key (listed in {})", revoked_keys().string()));
    }
    return invalid(
        fmt::format("does not match what it claims to sign ({}'s key, other content)", principal));
}

}  // namespace acetate
