// An allocator for large arrays filled at once (the exact table's 1.8 MB): memory mapped on its own,
// 2 MB aligned and marked for transparent huge pages, so filling it costs one page fault per 2 MB
// instead of one per 4 KB. In a virtual machine with shadow page tables a 4 KB fault costs about
// 10 us (measured on the development machine), which made loading the exact table 10 ms of every
// command. Requests under 256 KB, and systems without madvise(MADV_HUGEPAGE), use operator new.
//
//   std::vector<float, HugePageAllocator<float>> ln_y(n);
#pragma once

#include <cstddef>
#include <new>

namespace bssrdf {

void* allocate_huge_pages(std::size_t bytes);               // throws std::bad_alloc
void free_huge_pages(void* p, std::size_t bytes) noexcept;  // bytes: as allocated

template <class T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_alloc();
    return static_cast<T*>(allocate_huge_pages(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t n) noexcept { free_huge_pages(p, n * sizeof(T)); }
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace bssrdf
