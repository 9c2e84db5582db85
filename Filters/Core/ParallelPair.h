// Two pieces of work side by side: the Delaunay kernel's halves of space, and the halves of
// its sorting and copying loops. The machines this runs on have two or more cores; results
// never depend on whether the pieces ran on one thread or two.
#pragma once

#include <cstddef>
#include <cstdlib>
#include <exception>
#include <system_error>
#include <thread>

namespace tetmesher
{

// True when a second thread is worth starting: `threads` as DelaunayOptions::threads (0:
// when the machine has two CPUs or more, unless the environment variable TETMESHER_THREADS is
// 1; read on every call, so that a test can set it).
inline bool wantTwoThreads(int threads)
{
  if (threads == 0)
  {
    const char* setting = std::getenv("TETMESHER_THREADS");
    if (setting && std::atoi(setting) == 1)
      return false;
    // Asked once: glibc reads /sys/devices/system/cpu/online on every call.
    static const unsigned cpus = std::thread::hardware_concurrency();
    return cpus >= 2;
  }
  return threads >= 2;
}

// Runs work(0) and work(1): on two threads when twoThreads (and a thread can be started),
// else one after the other. An exception of either (bad_alloc) is rethrown here once both
// have stopped, as a one-thread run would throw it.
template<typename Work>
void runPair(bool twoThreads, Work&& work)
{
  std::exception_ptr failure;
  std::thread other;
  if (twoThreads)
    try
    {
      other = std::thread(
        [&work, &failure]
        {
          try
          {
            work(1);
          }
          catch (...)
          {
            failure = std::current_exception();
          }
        });
    }
    catch (const std::system_error&)
    {
    }
  try
  {
    work(0);
  }
  catch (...)
  {
    if (other.joinable())
      other.join();
    throw;
  }
  if (other.joinable())
    other.join();
  else
    work(1);
  if (failure)
    std::rethrow_exception(failure);
}

// body(0, 0, middle) and body(1, middle, end), side by side when twoThreads. The caller fixes
// the split (not the thread count), so what each half gathers, and the order the caller
// joins them in, is the same on one thread or two.
template<typename Index, typename Body>
void splitAt(bool twoThreads, Index middle, Index end, Body&& body)
{
  runPair(twoThreads,
    [&](int k)
    {
      if (k == 0)
        body(0, Index(0), middle);
      else
        body(1, middle, end);
    });
}

// Calls body(begin, end) on the two halves of [0, count), side by side when twoThreads and
// count reaches minCount.
template<typename Body>
void forHalves(std::size_t count, bool twoThreads, std::size_t minCount, Body&& body)
{
  if (!twoThreads || count < minCount)
  {
    body(std::size_t(0), count);
    return;
  }
  const std::size_t middle = count / 2;
  runPair(true,
    [&](int k)
    {
      if (k == 0)
        body(std::size_t(0), middle);
      else
        body(middle, count);
    });
}

} // namespace tetmesher
