#include "lodforge/core/huge_pages.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace lodforge {

void advise_huge_pages(const void* begin, const void* end) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const std::uintptr_t lo = (reinterpret_cast<std::uintptr_t>(begin) + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t hi = reinterpret_cast<std::uintptr_t>(end) & ~(kHuge - 1);
  // The advice is a hint: a kernel without transparent huge pages refuses
  // it, and the pages are then the usual ones.
  if (hi > lo) (void)madvise(reinterpret_cast<void*>(lo), hi - lo, MADV_HUGEPAGE);
#else
  (void)begin;
  (void)end;
#endif
}

}  // namespace lodforge
