// The hot loops' arrays on cache lines (CacheAligned.h): where they start, and that their
// values, size, copies and swaps are a vector's.

#include "CacheAligned.h"

#include <catch2/catch.hpp>

#include <cstdint>
#include <utility>
#include <vector>

using namespace snaresim;

namespace
{
bool onLine(const void* p) { return reinterpret_cast<std::uintptr_t>(p) % kCacheLine == 0; }
} // namespace

TEST_CASE("an aligned vector starts on a cache line whatever its size and element", "[cache]")
{
    for (std::size_t count : { 1u, 3u, 17u, 100u, 4099u })
    {
        INFO("count " << count);
        AlignedVector<double> d(count, 2.5);
        AlignedVector<float> f(count, 1.5f);
        AlignedVector<int> i(count, 7);
        CHECK(onLine(d.data()));
        CHECK(onLine(f.data()));
        CHECK(onLine(i.data()));
        AlignedVector<double> copy = d;
        CHECK(onLine(copy.data()));
        CHECK(copy == d);
        d.assign(count + 5, 0.0); // reallocated
        CHECK(onLine(d.data()));
    }
}

TEST_CASE("a row-aligned grid starts its row 1 on a cache line and holds a grid's values", "[cache]")
{
    for (int width = 1; width <= 70; ++width)
    {
        INFO("width " << width);
        const std::size_t count = (std::size_t) width * (std::size_t) width;
        RowAlignedGrid<float> f;
        f.assign(count, width, 0.25f);
        RowAlignedGrid<double> d;
        d.assign(count, width, -1.0);
        CHECK(onLine(f.data() + width));
        CHECK(onLine(d.data() + width));
        REQUIRE(f.size() == count);
        REQUIRE(d.size() == count);
        CHECK(f.end() - f.begin() == (std::ptrdiff_t) count);
        bool all = true;
        for (float v : f)
            all = all && v == 0.25f;
        CHECK(all);

        std::vector<double> values(count);
        for (std::size_t i = 0; i < count; ++i)
            values[i] = 0.5 * (double) i;
        RowAlignedGrid<float> from;
        from.assign(values.begin(), values.end(), width); // from a range, converted
        CHECK(onLine(from.data() + width));
        REQUIRE(from.size() == count);
        bool converted = true;
        for (std::size_t i = 0; i < count; ++i)
            converted = converted && from[i] == (float) values[i];
        CHECK(converted);

        for (std::size_t i = 0; i < count; ++i)
            f[i] = (float) i;
        RowAlignedGrid<float> copy = f; // a copy keeps the layout
        CHECK(onLine(copy.data() + width));
        RowAlignedGrid<float> other;
        other.assign(count, width, 0.0f);
        std::swap(other, copy); // the time levels' rotation
        CHECK(onLine(other.data() + width));
        bool same = true;
        for (std::size_t i = 0; i < count; ++i)
            same = same && other[i] == (float) i && other.data()[i] == f[i];
        CHECK(same);
    }
}
