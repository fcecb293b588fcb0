// The robustness suite: inputs built to crash the toolkit or to make it work
// without bound (huge and tiny coordinates, deep and doubling sharing, inline
// chains and DAGs, FIFOs and link loops as inlines, gzip bombs, huge
// polygons and headers, huge counts and resolutions), each run through the
// `lodforge` command in a child with a time and memory limit. Every case must
// end by itself within its limit with exit code 0 or 1, no signal, a message
// on failure ("error: ..." naming the file, never "out of memory" or an
// internal error), and nothing at the output path when it fails. The files
// are generated here, small, at test time.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "core/temp_dir.h"

namespace lodforge {
namespace {

namespace fs = std::filesystem;

#ifdef LODFORGE_SANITIZED
// Instrumented code runs 2-5 times slower and maps its shadow memory, which
// an address-space limit would refuse: the sanitizer bounds the memory.
constexpr double kSeconds = 40;
#else
constexpr double kSeconds = 10;
#endif
constexpr std::uint64_t kMemory = std::uint64_t{2} << 30;

struct Outcome {
  int exit_code = -1;  ///< -1: killed or died by a signal
  int signal = 0;
  bool timed_out = false;
  double seconds = 0;
  long max_rss_kb = 0;
  std::string err;
};

std::string read_all(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

class Robustness : public testing::TempDirTest {
 protected:
  // Runs lodforge ARGS in dir_ with the limits; standard output is dropped.
  Outcome run(const std::vector<std::string>& args) {
    const fs::path err = dir_ / ".stderr";
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = fork();
    if (pid == 0) {
      if (chdir(dir_.c_str()) != 0) _exit(127);
      const int null = open("/dev/null", O_RDWR);
      const int e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      dup2(null, 0);
      dup2(null, 1);
      dup2(e, 2);
#ifdef LODFORGE_SANITIZED
      setenv("ASAN_OPTIONS", "detect_leaks=0:hard_rss_limit_mb=2048:abort_on_error=1", 1);
#else
      const rlimit as{kMemory, kMemory};
      setrlimit(RLIMIT_AS, &as);
#endif
      std::vector<char*> argv{const_cast<char*>(LODFORGE_EXE)};
      for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
      argv.push_back(nullptr);
      execv(LODFORGE_EXE, argv.data());
      _exit(127);
    }
    Outcome o;
    int status = 0;
    rusage usage{};
    while (true) {
      const pid_t done = wait4(pid, &status, WNOHANG, &usage);
      o.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      if (done == pid) break;
      if (o.seconds > kSeconds) {
        o.timed_out = true;
        kill(pid, SIGKILL);
        wait4(pid, &status, 0, &usage);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
    o.max_rss_kb = usage.ru_maxrss;
    o.err = read_all(err);
    fs::remove(err);
    return o;
  }

  // Runs a case: it must end by itself, within the limits, with 0 or 1 and a
  // message, and leave nothing at `output` (if given) when it fails. With
  // `expect_error`, it must fail with a message containing that text.
  void check(const std::vector<std::string>& args, const std::string& expect_error = "",
             const std::string& output = "") {
    std::string line = "lodforge";
    for (const auto& a : args) line += " " + a;
    SCOPED_TRACE(line);
    if (!output.empty()) fs::remove(dir_ / output);
    const Outcome o = run(args);
    EXPECT_FALSE(o.timed_out) << "still running after " << kSeconds << " s";
    EXPECT_EQ(o.signal, 0) << o.err;
    EXPECT_TRUE(o.exit_code == 0 || o.exit_code == 1) << "exit " << o.exit_code << "\n" << o.err;
    EXPECT_LE(std::uint64_t(o.max_rss_kb) * 1024, kMemory) << o.max_rss_kb << " kB";
    EXPECT_THAT(o.err, ::testing::Not(::testing::HasSubstr("out of memory")));
    EXPECT_THAT(o.err, ::testing::Not(::testing::HasSubstr("internal error")));
    if (o.exit_code == 1) {
      EXPECT_THAT(o.err, ::testing::HasSubstr("error: "));
      if (!output.empty()) EXPECT_FALSE(fs::exists(dir_ / output)) << output << " was left";
    }
    if (!expect_error.empty()) {
      EXPECT_EQ(o.exit_code, 1) << o.err;
      EXPECT_THAT(o.err, ::testing::HasSubstr(expect_error));
    }
  }

  void write_binary_ply(const std::string& name, const std::vector<float>& xyz) {
    std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                    std::to_string(xyz.size() / 3) +
                    "\nproperty float x\nproperty float y\nproperty float z\n"
                    "element face 4\nproperty list uchar int vertex_indices\nend_header\n";
    s.append(reinterpret_cast<const char*>(xyz.data()), xyz.size() * sizeof(float));
    const std::int32_t faces[4][3] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    for (const auto& f : faces) {
      s.push_back(3);
      s.append(reinterpret_cast<const char*>(f), sizeof f);
    }
    write(name, s);
  }
};

// A tetrahedron whose corners are `a` (4 x 3 numbers) as OBJ text.
std::string tetrahedron_obj(const std::vector<float>& a) {
  std::ostringstream s;
  s.precision(9);
  for (int i = 0; i < 4; ++i)
    s << "v " << a[3 * i] << " " << a[3 * i + 1] << " " << a[3 * i + 2] << "\n";
  s << "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  return s.str();
}

const std::vector<float> kUnit = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};

std::vector<float> scaled(float s, float offset = 0) {
  std::vector<float> v = kUnit;
  for (float& x : v) x = x * s + offset;
  return v;
}

TEST_F(Robustness, HugeAndTinyCoordinates) {
  write("big.obj", tetrahedron_obj({0, 0, 0, 1e38f, 0, 0, 0, 1, 0, 0, 0, 1}));
  write("big_ascii.ply",
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty "
        "float y\nproperty float z\nelement face 4\nproperty list uchar int "
        "vertex_indices\nend_header\n0 0 0\n1e38 0 0\n0 1 0\n0 0 1\n3 0 2 1\n"
        "3 0 1 3\n3 0 3 2\n3 1 2 3\n");
  write_binary_ply("big_binary.ply", {0, 0, 0, 1e38f, 0, 0, 0, 1, 0, 0, 0, 1});
  write("all_big.obj", tetrahedron_obj(scaled(1e38f, -1e38f)));
  write("all_tiny.obj", tetrahedron_obj(scaled(1e-38f)));
  for (const char* f : {"big.obj", "big_ascii.ply", "big_binary.ply"}) {
    check({"mco", "build", f, "-o", "out.mco"}, std::string("error: ") + f + ": a coordinate",
          "out.mco");
    check({"simplify", f, "-o", "out.obj", "--ratio", "0.5"}, "a coordinate", "out.obj");
    check({"render", f, "-o", "out.png"}, "a coordinate", "out.png");
  }
  for (const char* f : {"all_big.obj", "all_tiny.obj"})
    check({"compare", f, f}, std::string("error: ") + f + ": ");
  // Inside the range, far from the origin and small: these work.
  write("far.obj", tetrahedron_obj(scaled(1e3f, 5e8f)));
  write("small.obj", tetrahedron_obj(scaled(1e-6f)));
  for (const char* f : {"far.obj", "small.obj"}) {
    check({"compare", f, f});
    check({"simplify", f, "-o", "out.obj", "--ratio", "0.5"});
  }
  // A scene: the IndexedFaceSet's coordinates and a primitive's size.
  write("big.wrl",
        "#VRML V1.0 ascii\nSeparator { Coordinate3 { point [0 0 0, 1e38 0 0, 0 1 0] }\n"
        "IndexedFaceSet { coordIndex [0, 1, 2] } }\n");
  write("cylinder.wrl", "#VRML V1.0 ascii\nSeparator { Cylinder { radius 1e38 } }\n");
  write("negative.wrl", "#VRML V1.0 ascii\nSeparator { Cylinder { radius -2 } }\n");
  for (const char* f : {"big.wrl", "cylinder.wrl"})
    check({"lod", f, "-o", "out.wrl"}, "ranges must be finite", "out.wrl");
  check({"lod", "negative.wrl", "-o", "out.wrl"});
  EXPECT_THAT(read_all(dir_ / "out.wrl"), ::testing::Not(::testing::HasSubstr("inf")));
}

TEST_F(Robustness, HugeCounts) {
  write("tet.obj", tetrahedron_obj(kUnit));
  check({"compare", "tet.obj", "tet.obj", "--samples", "18446744073709551615"},
        "more than the memory budget");
  check({"mco", "build", "tet.obj", "-o", "out.mco", "--resolution", "1000", "--max-memory", "1"},
        "error: tet.obj: mcoctree: the lattice at resolution 1000 needs about", "out.mco");
}

TEST_F(Robustness, NonNumbersInScenes) {
  write("nan.wrl", "#VRML V1.0 ascii\nSeparator { Sphere { radius nan } }\n");
  check({"info", "nan.wrl"});
  check({"lod", "nan.wrl", "-o", "out.wrl"}, "must be a finite size", "out.wrl");
}

// DEF/USE doubling at each level below one Cube ("billion laughs").
std::string doubling_scene(int levels) {
  std::string s = "#VRML V1.0 ascii\nSeparator {\n DEF L0 Cube {}\n";
  for (int i = 1; i <= levels; ++i)
    s += " DEF L" + std::to_string(i) + " Separator { USE L" + std::to_string(i - 1) + " USE L" +
         std::to_string(i - 1) + " }\n";
  return s + "}\n";
}

TEST_F(Robustness, DoublingSharing) {
  write("laughs20.wrl", doubling_scene(20));
  write("laughs40.wrl", doubling_scene(40));
  for (const char* f : {"laughs20.wrl", "laughs40.wrl"}) {
    const std::string refused = std::string("error: ") + f + ":";
    check({"info", f}, refused);
    check({"format", f, "-o", "out.wrl"}, refused, "out.wrl");
    check({"lod", f, "-o", "out.wrl"}, refused, "out.wrl");
    check({"render", f, "-o", "out.png"}, refused, "out.png");
    check({"simplify", f, "-o", "out.obj", "--ratio", "0.5"}, refused, "out.obj");
    check({"compare", f, f}, refused);
  }
}

TEST_F(Robustness, InlineChainsAndDags) {
  const int chain = 400;
  for (int i = 0; i < chain; ++i)
    write("chain/c" + std::to_string(i) + ".wrl",
          "#VRML V1.0 ascii\nSeparator { " +
              (i + 1 < chain ? "WWWInline { name \"c" + std::to_string(i + 1) + ".wrl\" }"
                             : std::string("Cube {}")) +
              " }\n");
  for (const char* cmd : {"info", "format", "lod"}) {
    std::vector<std::string> args = {cmd, "--inline", "chain/c0.wrl"};
    if (std::string(cmd) != "info") args.insert(args.end(), {"-o", "out.wrl"});
    check(args, "nodes nested deeper than 256 levels", "out.wrl");
  }
  const int dag = 30;
  for (int i = 0; i < dag; ++i) {
    const std::string next = "WWWInline { name \"d" + std::to_string(i + 1) + ".wrl\" }";
    write(
        "dag/d" + std::to_string(i) + ".wrl",
        "#VRML V1.0 ascii\nSeparator { " + (i + 1 < dag ? next + " " + next : "Cube {}") + " }\n");
  }
  check({"info", "--inline", "dag/d0.wrl"}, "goes past the limit of 10000 inlined files");
  check({"lod", "--inline", "dag/d0.wrl", "-o", "out.wrl"}, "refused", "out.wrl");
}

TEST_F(Robustness, InlinesThatAreNotRegularFiles) {
  ASSERT_EQ(mkfifo((dir_ / "pipe.wrl").c_str(), 0600), 0);
  write("fifo.wrl", "#VRML V1.0 ascii\nSeparator { WWWInline { name \"pipe.wrl\" } }\n");
  check({"info", "--inline", "fifo.wrl"}, "fifo.wrl:2: WWWInline 'pipe.wrl' is not a regular file");
  fs::create_symlink("b.wrl", dir_ / "a.wrl");
  fs::create_symlink("a.wrl", dir_ / "b.wrl");
  write("loop.wrl", "#VRML V1.0 ascii\nSeparator { WWWInline { name \"a.wrl\" } }\n");
  check({"format", "--inline", "loop.wrl", "-o", "out.wrl"},
        "loop.wrl:2: WWWInline 'a.wrl' cannot be resolved", "out.wrl");
}

// `header` then `size` bytes of spaces then `tail`, gzip-compressed, streamed
// so that the test never holds the inflated data.
void write_gzip_bomb(const fs::path& path, const std::string& header, std::size_t size,
                     const std::string& tail) {
  gzFile f = gzopen(path.c_str(), "wb9");
  ASSERT_NE(f, nullptr);
  gzwrite(f, header.data(), unsigned(header.size()));
  const std::string spaces(std::size_t{1} << 22, ' ');
  for (std::size_t done = 0; done < size; done += spaces.size())
    gzwrite(f, spaces.data(), unsigned(spaces.size()));
  gzwrite(f, tail.data(), unsigned(tail.size()));
  gzclose(f);
}

TEST_F(Robustness, GzipBombs) {
  const std::size_t size = std::size_t{128} << 20;  // 128 MiB from about 0.1 MB: past 64 MiB
  write_gzip_bomb(dir_ / "bomb.wrl.gz", "#VRML V1.0 ascii\n", size, "Separator { Cube {} }\n");
  write_gzip_bomb(dir_ / "bomb.ply.gz",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float "
                  "y\nproperty float z\nelement face 1\nproperty list uchar int "
                  "vertex_indices\nend_header\n",
                  size, "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  check({"info", "bomb.wrl.gz"}, "bomb.wrl.gz: the gzip data inflates to more than");
  check({"lod", "bomb.wrl.gz", "-o", "out.wrl"}, "possible gzip bomb", "out.wrl");
  check({"simplify", "bomb.ply.gz", "-o", "out.obj", "--ratio", "0.5"},
        "bomb.ply.gz: the gzip data inflates to more than", "out.obj");
}

// One polygon of n corners: a circle (convex) or a star (every other corner
// in by half), as OBJ, PLY and OFF.
std::vector<std::array<float, 3>> polygon(int n, bool star) {
  std::vector<std::array<float, 3>> p;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    const double r = star && i % 2 ? 0.5 : 1.0;
    p.push_back({float(r * std::cos(a)), float(r * std::sin(a)), 0});
  }
  return p;
}

TEST_F(Robustness, HugePolygonsAndHeaders) {
  const int n = 100'000;
  for (bool star : {false, true}) {
    const auto p = polygon(n, star);
    std::ostringstream obj, ply, off, face;
    ply << "ply\nformat ascii 1.0\nelement vertex " << n
        << "\nproperty float x\nproperty float y\nproperty float z\nelement face 1\n"
           "property list int int vertex_indices\nend_header\n";
    off << "OFF\n" << n << " 1 0\n";
    for (const auto& v : p) {
      obj << "v " << v[0] << " " << v[1] << " " << v[2] << "\n";
      ply << v[0] << " " << v[1] << " " << v[2] << "\n";
      off << v[0] << " " << v[1] << " " << v[2] << "\n";
    }
    obj << "f";
    ply << n;
    off << n;
    for (int i = 0; i < n; ++i) {
      obj << " " << i + 1;
      ply << " " << i;
      off << " " << i;
    }
    const std::string name = star ? "star" : "circle";
    write(name + ".obj", obj.str() + "\n");
    write(name + ".ply", ply.str() + "\n");
    write(name + ".off", off.str() + "\n");
  }
  for (const char* f : {"circle.obj", "circle.ply", "circle.off", "star.obj"}) {
    check({"simplify", f, "-o", "out.obj", "--ratio", "0.5"});
    check({"render", f, "-o", "out.png"});
  }
  check({"compare", "circle.obj", "circle.ply"});
  check({"mco", "build", "circle.off", "-o", "out.mco"}, "", "out.mco");
  // A header of 200 000 properties.
  std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty "
      "float y\nproperty float z\n";
  for (int i = 0; i < 200'000; ++i) header += "property uchar p" + std::to_string(i) + "\n";
  header += "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string zeros;
  for (int i = 0; i < 200'000; ++i) zeros += " 0";
  write("props.ply",
        header + "0 0 0" + zeros + "\n1 0 0" + zeros + "\n0 1 0" + zeros + "\n3 0 1 2\n");
  check({"simplify", "props.ply", "-o", "out.obj", "--ratio", "0.5"});
}

}  // namespace
}  // namespace lodforge
