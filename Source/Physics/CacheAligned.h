#pragma once
// Arrays that start on a cache line (64 bytes), for the hot loops' vector loads: a load of
// AVX-512's 64 bytes (or AVX2's 32) from an array that starts on a line never straddles two
// lines, where one of an array that malloc aligns to 16 bytes straddles two in every one or
// two loads, each such load costing about two. The values and their order are the same.

#include <cstddef>
#include <new>
#include <vector>

namespace snaresim
{

inline constexpr std::size_t kCacheLine = 64;

template <class T>
struct CacheLineAllocator
{
    using value_type = T;
    CacheLineAllocator() = default;
    template <class U>
    CacheLineAllocator(const CacheLineAllocator<U>&) noexcept
    {}
    T* allocate(std::size_t count) { return static_cast<T*>(::operator new(count * sizeof(T), std::align_val_t(kCacheLine))); }
    void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(kCacheLine)); }
    template <class U>
    bool operator==(const CacheLineAllocator<U>&) const noexcept
    {
        return true;
    }
};

template <class T>
using AlignedVector = std::vector<T, CacheLineAllocator<T>>;

// A square grid's values, width x width row by row, stored so that row 1 starts on a cache
// line: the free update's whole-grid loop starts there (Membrane::computeFree).
template <class T>
class RowAlignedGrid
{
public:
    // count values (width x width), all `value`.
    void assign(std::size_t count, int width, T value)
    {
        lead = leadFor(width);
        store.assign(count + lead, value);
    }
    // The values of [first, last) (width x width of them), converted to T.
    template <class Iterator>
    void assign(Iterator first, Iterator last, int width)
    {
        lead = leadFor(width);
        store.assign(lead, T {});
        store.insert(store.end(), first, last);
    }
    T* data() noexcept { return store.data() + lead; }
    const T* data() const noexcept { return store.data() + lead; }
    std::size_t size() const noexcept { return store.size() - lead; }
    T& operator[](std::size_t i) noexcept { return store[lead + i]; }
    const T& operator[](std::size_t i) const noexcept { return store[lead + i]; }
    T* begin() noexcept { return data(); }
    T* end() noexcept { return data() + size(); }
    const T* begin() const noexcept { return data(); }
    const T* end() const noexcept { return data() + size(); }

private:
    static std::size_t leadFor(int width)
    {
        constexpr std::size_t perLine = kCacheLine / sizeof(T);
        return (perLine - (std::size_t) width % perLine) % perLine;
    }
    AlignedVector<T> store;
    std::size_t lead = 0; // values before row 0, so that row 1 starts on a line
};

} // namespace snaresim
