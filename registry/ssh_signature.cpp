#include "ssh_signature.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/child_process.hpp"

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
    int wait_status = 0;
    while (waitpid(pid, &wait_status, 0) < 0)
        if (errno != EINTR) return make_error(ErrorCode::Io, "lost the ssh-keygen child process");
    ToolRun run;
    run.status = WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1;
    run.out = read_text(output);
    run.err = read_text(errors);
    return run;
}

Result<void> invalid(std::string message) {
    return make_error(ErrorCode::InvalidInput, std::move(message));
}

}  // namespace

Result<std::string> ssh_sign(const fs::path& key, std::string_view message) {
    ScratchFolder scratch;
    if (scratch.path().empty())
        return make_error(ErrorCode::Io, "cannot create a temporary folder to sign in");
    const fs::path input = scratch.path() / "statement";
    if (!write_text(input, message))
        return make_error(ErrorCode::Io, fmt::format("{}: cannot write", input.string()));
    // With no file named, ssh-keygen signs its standard input and writes the signature to its
    // standard output.
    auto run = ssh_keygen({"-q", "-Y", "sign", "-f", key.string(), "-n", kSignatureNamespace},
                          input, scratch.path());
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

SignatureVerifier::SignatureVerifier(fs::path allowed_signers)
    : allowed_signers_(std::move(allowed_signers)) {}

fs::path SignatureVerifier::revoked_keys() const {
    return allowed_signers_.parent_path() / "revoked_keys";
}

Result<void> SignatureVerifier::verify(std::string_view principal, std::string_view message,
                                       std::string_view signature) const {
    if (signature.empty()) return invalid("is missing (the sign-off is not signed)");
    std::error_code ec;
    if (!fs::is_regular_file(allowed_signers_, ec))
        return make_error(ErrorCode::Io, fmt::format("cannot be checked: {}: no such file (the "
                                                     "allowed signers)",
                                                     allowed_signers_.string()));
    ScratchFolder scratch;
    if (scratch.path().empty())
        return make_error(ErrorCode::Io, "cannot create a temporary folder to verify in");
    const fs::path input = scratch.path() / "statement";
    const fs::path sig = scratch.path() / "statement.sig";
    if (!write_text(input, message) || !write_text(sig, signature))
        return make_error(ErrorCode::Io, "cannot write a temporary file to verify");

    std::vector<std::string> args = {"-Y", "verify",
                                     "-f", allowed_signers_.string(),
                                     "-I", std::string(principal),
                                     "-n", kSignatureNamespace,
                                     "-s", sig.string()};
    const bool has_revocations = fs::is_regular_file(revoked_keys(), ec);
    if (has_revocations) {
        args.push_back("-r");
        args.push_back(revoked_keys().string());
    }
    auto run = ssh_keygen(args, input, scratch.path());
    if (!run) return run.error();
    if (run->status == 0) return {};

    // Why, in the maintainer's terms: ssh-keygen says only "Could not verify signature".
    const fs::path empty = scratch.path() / "empty";
    write_text(empty, "");
    auto principals =
        ssh_keygen({"-Y", "find-principals", "-f", allowed_signers_.string(), "-s", sig.string()},
                   empty, scratch.path());
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
