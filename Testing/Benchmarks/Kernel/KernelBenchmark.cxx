// Delaunay kernel benchmark: our buildDelaunay against TetGen (the `tetgen` command line,
// run on a .node file) and CGAL's Delaunay_triangulation_3, on the same points.
//
// Rows: `ours` (large rounds in two halves on two threads, the default), `ours-1t` (the same
// mesh on one thread), `tetgen` (one thread), `cgal` (one thread) and `cgal-par` (CGAL's
// parallel insertion with TBB, on all CPUs, when TBB is found). Ratios are against `ours`.
// Every measurement runs in a forked child so that each one's peak RSS (getrusage) is its
// own. Wall time and CPU time (user + system, of all threads) are both reported.
// Each case runs every tool `--repeat` times, interleaved (ours, ours-1t, tetgen, cgal,
// cgal-par, then again), so that a burst of load from the machine's other users falls on one
// round rather than on one tool; each round's ratios are printed, then each tool's median run
// (by wall time) and the ratios of the medians. Default: 3 rounds, 1 for the 10M row. Usage:
// TetMesherKernelBenchmark [--quick] [--no-tetgen] [--no-cgal] [--no-10m] [--repeat N]
// [--only uniform|sphere|grid|grid-tenth]
#include "Delaunay.h"

#ifdef TETMESHER_BENCHMARK_CGAL
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#ifdef CGAL_LINKED_WITH_TBB
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Triangulation_vertex_base_3.h>
#endif
#endif

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace
{

struct Measurement
{
  double seconds = -1;
  double cpuSeconds = -1; // user + system time: on a shared machine, much steadier than wall
  double tets = 0;
  double peakRssBytes = 0; // peak resident set of the process doing the work
  double baseRssBytes = 0; // resident set before the work started (input points etc.)
};

double nowSeconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

double cpuTime(int who)
{
  rusage usage{};
  getrusage(who, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
    1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
}

double peakRss(int who)
{
  rusage usage{};
  getrusage(who, &usage);
  return static_cast<double>(usage.ru_maxrss) * 1024.0; // Linux reports kilobytes
}

// Runs `work` in a child process and returns what it measured (seconds < 0 on failure).
template<typename Work>
Measurement isolated(Work work)
{
  int fds[2];
  if (pipe(fds) != 0)
    return {};
  const pid_t pid = fork();
  if (pid == 0)
  {
    close(fds[0]);
    Measurement m = work();
    if (write(fds[1], &m, sizeof m) != static_cast<ssize_t>(sizeof m))
      _exit(1);
    _exit(0);
  }
  close(fds[1]);
  Measurement m;
  if (read(fds[0], &m, sizeof m) != static_cast<ssize_t>(sizeof m))
    m = Measurement{};
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  return m;
}

std::vector<double> makePoints(const std::string& kind, std::size_t n)
{
  std::vector<double> p;
  std::mt19937_64 gen(2024);
  std::uniform_real_distribution<double> u(0, 1);
  std::normal_distribution<double> g;
  if (kind == "grid" || kind == "grid-tenth")
  {
    // grid-tenth: the same grid in steps of 0.1 (each coordinate the double nearest i/10), not
    // a lattice of one power of two, so the kernel's small-lattice evaluation does not apply
    // and the co-spherical cells are decided by the filters and exact stages.
    const int m = static_cast<int>(std::lround(std::cbrt(static_cast<double>(n))));
    auto at = [&kind](int i) { return kind == "grid" ? double(i) : double(i) / 10; };
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j)
        for (int k = 0; k < m; ++k)
          p.insert(p.end(), { at(i), at(j), at(k) });
    return p;
  }
  p.reserve(3 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (kind == "sphere")
    {
      double x = g(gen), y = g(gen), z = g(gen), r = std::sqrt(x * x + y * y + z * z);
      p.insert(p.end(), { x / r, y / r, z / r });
    }
    else
      p.insert(p.end(), { u(gen), u(gen), u(gen) });
  }
  return p;
}

Measurement runOurs(const std::vector<double>& points, int threads)
{
  return isolated(
    [&points, threads]()
    {
      Measurement m;
      m.baseRssBytes = peakRss(RUSAGE_SELF);
      const double start = nowSeconds(), cpuStart = cpuTime(RUSAGE_SELF);
      tetmesher::TetMesh mesh;
      tetmesher::DelaunayOptions options;
      options.threads = threads;
      // The points as the caller has them (CGAL's interface takes its own point type, which
      // its row builds and times).
      const tetmesher::DelaunayResult r = tetmesher::buildDelaunay(
        mesh, points.data(), static_cast<tetmesher::VertexId>(points.size() / 3), options);
      m.seconds = nowSeconds() - start;
      m.cpuSeconds = cpuTime(RUSAGE_SELF) - cpuStart;
      if (!r.ok)
      {
        std::fprintf(stderr, "buildDelaunay failed: %s\n", r.error.c_str());
        m.seconds = -1;
      }
      m.tets = mesh.liveTetCount();
      m.peakRssBytes = peakRss(RUSAGE_SELF);
      return m;
    });
}

Measurement runTetGen(const std::vector<double>& points)
{
  const std::string base = "/tmp/tetmesher_bench_" + std::to_string(getpid());
  {
    FILE* f = std::fopen((base + ".node").c_str(), "w");
    if (!f)
      return {};
    const std::size_t n = points.size() / 3;
    std::fprintf(f, "%zu 3 0 0\n", n);
    for (std::size_t i = 0; i < n; ++i)
      std::fprintf(
        f, "%zu %.17g %.17g %.17g\n", i + 1, points[3 * i], points[3 * i + 1], points[3 * i + 2]);
    std::fclose(f);
  }
  Measurement m = isolated(
    [&base]()
    {
      Measurement r;
      // -Q quiet; -N -E -F: write no output files, so we time the tetrahedralization and
      // the reading of the .node file only.
      const std::string cmd = "tetgen -QNEF " + base + ".node > /dev/null 2>&1";
      const double start = nowSeconds(), cpuStart = cpuTime(RUSAGE_CHILDREN);
      const int rc = std::system(cmd.c_str());
      r.seconds = rc == 0 ? nowSeconds() - start : -1;
      r.cpuSeconds = cpuTime(RUSAGE_CHILDREN) - cpuStart;
      r.peakRssBytes = peakRss(RUSAGE_CHILDREN);
      return r;
    });
  std::remove((base + ".node").c_str());
  return m;
}

#ifdef TETMESHER_BENCHMARK_CGAL
Measurement runCgal(const std::vector<double>& points)
{
  return isolated(
    [&points]()
    {
      using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
      using Triangulation = CGAL::Delaunay_triangulation_3<Kernel>;
      Measurement m;
      m.baseRssBytes = peakRss(RUSAGE_SELF);
      const double start = nowSeconds(), cpuStart = cpuTime(RUSAGE_SELF);
      std::vector<Kernel::Point_3> pts;
      pts.reserve(points.size() / 3);
      for (std::size_t i = 0; i < points.size(); i += 3)
        pts.emplace_back(points[i], points[i + 1], points[i + 2]);
      Triangulation t(pts.begin(), pts.end());
      m.seconds = nowSeconds() - start;
      m.cpuSeconds = cpuTime(RUSAGE_SELF) - cpuStart;
      m.tets = static_cast<double>(t.number_of_finite_cells());
      m.peakRssBytes = peakRss(RUSAGE_SELF);
      return m;
    });
}

#ifdef CGAL_LINKED_WITH_TBB
Measurement runCgalParallel(const std::vector<double>& points)
{
  return isolated(
    [&points]()
    {
      using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
      using Tds = CGAL::Triangulation_data_structure_3<CGAL::Triangulation_vertex_base_3<Kernel>,
        CGAL::Delaunay_triangulation_cell_base_3<Kernel>,
        CGAL::Parallel_tag>;
      using Triangulation = CGAL::Delaunay_triangulation_3<Kernel, Tds>;
      Measurement m;
      m.baseRssBytes = peakRss(RUSAGE_SELF);
      const double start = nowSeconds(), cpuStart = cpuTime(RUSAGE_SELF);
      std::vector<Kernel::Point_3> pts;
      pts.reserve(points.size() / 3);
      double lo[3] = { points[0], points[1], points[2] }, hi[3] = { lo[0], lo[1], lo[2] };
      for (std::size_t i = 0; i < points.size(); i += 3)
      {
        pts.emplace_back(points[i], points[i + 1], points[i + 2]);
        for (int k = 0; k < 3; ++k)
        {
          lo[k] = std::min(lo[k], points[i + k]);
          hi[k] = std::max(hi[k], points[i + k]);
        }
      }
      // The locking grid over the points' box, 50 cells a side (CGAL's example).
      Triangulation::Lock_data_structure locks(
        CGAL::Bbox_3(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]), 50);
      Triangulation t(pts.begin(), pts.end(), &locks);
      m.seconds = nowSeconds() - start;
      m.cpuSeconds = cpuTime(RUSAGE_SELF) - cpuStart;
      m.tets = static_cast<double>(t.number_of_finite_cells());
      m.peakRssBytes = peakRss(RUSAGE_SELF);
      return m;
    });
}
#endif
#endif

void report(const char* who, const Measurement& m, double points, const Measurement& ours)
{
  if (m.seconds < 0)
  {
    std::printf("  %-8s failed or skipped\n", who);
    return;
  }
  std::printf("  %-8s %8.3f s  %6.3f Mpts/s", who, m.seconds, points / m.seconds * 1e-6);
  if (m.tets > 0)
    std::printf("  %6.3f Mtets/s  %9.0f tets  %6.1f B/tet (peak-base)",
      m.tets / m.seconds * 1e-6,
      m.tets,
      (m.peakRssBytes - m.baseRssBytes) / m.tets);
  std::printf("  peak RSS %7.1f MiB", m.peakRssBytes / (1024.0 * 1024.0));
  if (ours.seconds > 0 && m.seconds > 0)
    std::printf("  time/ours %.2fx", m.seconds / ours.seconds);
  if (m.cpuSeconds > 0)
    std::printf("  cpu %.3f s", m.cpuSeconds);
  if (ours.cpuSeconds > 0 && m.cpuSeconds > 0)
    std::printf("  cpu/ours %.2fx", m.cpuSeconds / ours.cpuSeconds);
  std::printf("\n");
}

} // namespace

int main(int argc, char** argv)
{
  bool quick = false, tetgen = true, cgal = true, tenMillion = true;
  int repeat = 0; // 0: the default (3, or 1 for 10M points)
  // --only KIND: that point set alone (uniform, sphere, grid; grid-tenth, the grid in steps of
  // 0.1, runs only when asked for)
  std::string only;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--only" && i + 1 < argc &&
      (std::string(argv[i + 1]) == "uniform" || std::string(argv[i + 1]) == "sphere" ||
        std::string(argv[i + 1]) == "grid" || std::string(argv[i + 1]) == "grid-tenth"))
      only = argv[++i];
    else if (a == "--quick")
      quick = true;
    else if (a == "--no-tetgen")
      tetgen = false;
    else if (a == "--no-cgal")
      cgal = false;
    else if (a == "--no-10m")
      tenMillion = false;
    else if (a == "--repeat" && i + 1 < argc && std::atoi(argv[i + 1]) > 0)
      repeat = std::atoi(argv[++i]);
    else
    {
      std::fprintf(stderr,
        "usage: %s [--quick] [--no-tetgen] [--no-cgal] [--no-10m] [--repeat N] "
        "[--only uniform|sphere|grid|grid-tenth]\n",
        argv[0]);
      return 2;
    }
  }
  struct Case
  {
    std::string kind;
    std::size_t n;
  };
  std::vector<Case> cases;
  if (quick)
    cases = {
      { "uniform", 100000 }, { "sphere", 100000 }, { "grid", 27000 }, { "grid-tenth", 27000 }
    };
  else
  {
    cases = {
      { "uniform", 1000000 }, { "sphere", 1000000 }, { "grid", 1000000 }, { "grid-tenth", 1000000 }
    };
    if (tenMillion)
      cases.push_back({ "uniform", 10000000 });
  }
  for (const Case& c : cases)
  {
    if (only.empty() ? c.kind == "grid-tenth" : c.kind != only)
      continue;
    const std::vector<double> points = makePoints(c.kind, c.n);
    const double n = static_cast<double>(points.size() / 3);
    const int rounds = repeat > 0 ? repeat : c.n > 5000000 ? 1 : 3;
    struct Tool
    {
      const char* name;
      std::function<Measurement()> run;
      std::vector<Measurement> runs;
    };
    std::vector<Tool> tools;
    tools.push_back({ "ours", [&points]() { return runOurs(points, 0); }, {} });
    tools.push_back({ "ours-1t", [&points]() { return runOurs(points, 1); }, {} });
    if (tetgen)
      tools.push_back({ "tetgen", [&points]() { return runTetGen(points); }, {} });
#ifdef TETMESHER_BENCHMARK_CGAL
    if (cgal)
    {
      tools.push_back({ "cgal", [&points]() { return runCgal(points); }, {} });
#ifdef CGAL_LINKED_WITH_TBB
      tools.push_back({ "cgal-par", [&points]() { return runCgalParallel(points); }, {} });
#endif
    }
#else
    (void)cgal;
#endif
    std::printf("%s, %.0f points, %d round%s\n", c.kind.c_str(), n, rounds, rounds > 1 ? "s" : "");
    std::fflush(stdout);
    for (int r = 0; r < rounds; ++r)
    {
      for (Tool& tool : tools)
        tool.runs.push_back(tool.run());
      // This round's wall times, and each tool's time as a multiple of ours.
      std::printf("  round %d:", r + 1);
      const double oursSeconds = tools[0].runs.back().seconds;
      for (const Tool& tool : tools)
      {
        const double s = tool.runs.back().seconds;
        if (s < 0)
          std::printf("  %s failed", tool.name);
        else if (&tool == &tools[0] || oursSeconds <= 0)
          std::printf("  %s %.3f s", tool.name, s);
        else
          std::printf("  %s %.3f s (%.2fx)", tool.name, s, s / oursSeconds);
      }
      std::printf("\n");
      std::fflush(stdout);
    }
    // Each tool's median run by wall time (the upper one of an even count).
    auto median = [](std::vector<Measurement> runs)
    {
      std::sort(runs.begin(),
        runs.end(),
        [](const Measurement& a, const Measurement& b) { return a.seconds < b.seconds; });
      return runs[runs.size() / 2];
    };
    const Measurement ours = median(tools[0].runs);
    if (rounds > 1)
      std::printf("  medians of %d rounds:\n", rounds);
    for (const Tool& tool : tools)
      report(tool.name, median(tool.runs), n, &tool == &tools[0] ? Measurement{} : ours);
    std::fflush(stdout);
  }
  return 0;
}
