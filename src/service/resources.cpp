#include "gpfd/service/resources.hpp"

#include <fmt/format.h>
#include <tbb/info.h>
#include <unistd.h>

#include <cstdio>

#include "gpfd/util/error.hpp"

namespace gpfd::service {

int usableThreads(int requested) {
  const int cores = tbb::info::default_concurrency();
  if (requested <= cores) return requested;
  static bool told = false;
  if (!told) {
    std::fprintf(stderr, "note: --threads %d is more than the %d cores available; using %d\n",
                 requested, cores, cores);
    told = true;
  }
  return cores;
}

void requireMemory(double bytes, const std::string& what, const std::string& where) {
  const double machine =
      static_cast<double>(::sysconf(_SC_PHYS_PAGES)) * static_cast<double>(::sysconf(_SC_PAGESIZE));
  if (machine > 0 && bytes > machine) {
    constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;
    throw InputError(fmt::format("{} would need about {:.0f} GiB of memory, more than this "
                                 "machine's {:.0f} GiB",
                                 what, bytes / kGiB, machine / kGiB),
                     where);
  }
}

}  // namespace gpfd::service
