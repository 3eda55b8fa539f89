#include "harness/snapshot/AnimationWriter.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>

#include "core/Errors.h"

extern char** environ;

namespace cdb {

namespace {

// The first executable `name` on PATH.
std::optional<std::filesystem::path> onPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string dirs = path != nullptr ? path : "/usr/bin:/bin";
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t colon = std::min(dirs.find(':', start), dirs.size());
    const std::filesystem::path candidate =
        std::filesystem::path(colon > start ? dirs.substr(start, colon - start) : ".") / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = colon + 1;
  }
  return std::nullopt;
}

// Debian's python3 has python3-pil; an interpreter earlier on PATH (a venv) may not.
std::optional<std::filesystem::path> python() {
  if (::access("/usr/bin/python3", X_OK) == 0) return std::filesystem::path("/usr/bin/python3");
  return onPath("python3");
}

bool isGif(const std::filesystem::path& out) { return out.extension() == ".gif"; }
bool isMp4(const std::filesystem::path& out) { return out.extension() == ".mp4"; }

// Runs `argv` and waits; its output goes where ours goes. Returns the exit status (-1: a signal).
int runTool(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int err = ::posix_spawn(&pid, args[0], nullptr, nullptr, args.data(), environ);
  if (err != 0) throw RunError(argv[0] + ": cannot start (" + std::strerror(err) + ")");
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw RunError(argv[0] + ": lost track of the process");
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

void checkAnimationTool(const std::filesystem::path& out) {
  if (isGif(out)) {
    if (!python())
      throw InputError("--out " + out.string() +
                       ": an animated GIF needs python3 with Pillow (Debian: "
                       "apt-get install python3-pil); none found");
  } else if (isMp4(out)) {
    if (!onPath("ffmpeg"))
      throw InputError("--out " + out.string() +
                       ": an MP4 needs ffmpeg, which is not on PATH; "
                       "write a .gif instead (made with Pillow)");
  } else {
    throw InputError("--out " + out.string() +
                     ": with --frames expected an animation, FILE.gif or FILE.mp4 "
                     "(the numbered PNGs go beside it)");
  }
}

void writeAnimation(const std::filesystem::path& out,
                    const std::vector<std::filesystem::path>& pictures, int fps) {
  checkAnimationTool(out);
  if (pictures.empty()) throw RunError(out.string() + ": no pictures to animate");
  std::vector<std::string> argv;
  std::filesystem::path tmp;
  if (isGif(out)) {
    argv = {python()->string(),
            std::string(CDBENCH_SOURCE_DIR) + "/scripts/animate.py",
            "--out",
            out.string(),
            "--fps",
            std::to_string(fps)};
    for (const auto& p : pictures) argv.push_back(p.string());
  } else {
    // ffmpeg's concat list names the exact pictures, each shown 1/fps seconds.
    const std::filesystem::path list = pictures.front().parent_path() / "ffmpeg-input.txt";
    {
      std::ofstream l(list);
      l << "ffconcat version 1.0\n";
      for (const auto& p : pictures)
        l << "file '" << std::filesystem::absolute(p).string() << "'\nduration " << 1.0 / fps
          << "\n";
      if (!l) throw RunError(list.string() + ": cannot write");
    }
    tmp = out.parent_path() / (out.stem().string() + ".tmp." + std::to_string(::getpid()) + ".mp4");
    argv = {onPath("ffmpeg")->string(),
            "-hide_banner",
            "-loglevel",
            "error",
            "-y",
            "-f",
            "concat",
            "-safe",
            "0",
            "-i",
            list.string(),
            "-vf",
            "fps=" + std::to_string(fps) + ",pad=ceil(iw/2)*2:ceil(ih/2)*2",
            "-pix_fmt",
            "yuv420p",
            tmp.string()};
  }
  const int status = runTool(argv);
  if (status != 0) {
    std::error_code ec;
    if (!tmp.empty()) std::filesystem::remove(tmp, ec);
    throw RunError(out.string() + ": " +
                   std::filesystem::path(argv[isGif(out) ? 1 : 0]).filename().string() +
                   " failed (exit status " + std::to_string(status) + ")");
  }
  if (!tmp.empty()) {
    std::error_code ec;
    std::filesystem::rename(tmp, out, ec);
    if (ec) {
      std::filesystem::remove(tmp, ec);
      throw RunError(out.string() + ": cannot rename into place (" + ec.message() + ")");
    }
  }
}

}  // namespace cdb
