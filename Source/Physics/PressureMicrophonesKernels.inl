// The microphones' loops (the cells' volume accelerations each step, the taps' sums each block),
// compiled once per vector target by PerVectorTarget.inl: no include guard, no includes.

using TapRow = float __attribute__((vector_size(32))); // a source's A at a block's 8 steps

// s[lane][step] into tile[step 8 + lane]: an 8 x 8 transpose in registers.
inline void storeTransposed(const TapRow* s, float* __restrict tile)
{
    using Row = TapRow;
    // pairs of rows interleaved by 1, 2 and 4 floats
    using Index = int __attribute__((vector_size(32)));
#if defined(__clang__)
#define SNARESIM_SHUFFLE(x, y, ...) __builtin_shufflevector(x, y, __VA_ARGS__)
#else
#define SNARESIM_SHUFFLE(x, y, ...) __builtin_shuffle(x, y, Index { __VA_ARGS__ })
#endif
    Row t[8], u[8];
#pragma GCC unroll 4
    for (int i = 0; i < 8; i += 2)
    {
        t[i] = SNARESIM_SHUFFLE(s[i], s[i + 1], 0, 8, 1, 9, 4, 12, 5, 13);
        t[i + 1] = SNARESIM_SHUFFLE(s[i], s[i + 1], 2, 10, 3, 11, 6, 14, 7, 15);
    }
#pragma GCC unroll 2
    for (int i = 0; i < 8; i += 4)
#pragma GCC unroll 2
        for (int j = 0; j < 2; ++j)
        {
            u[i + j] = SNARESIM_SHUFFLE(t[i + j], t[i + j + 2], 0, 1, 8, 9, 4, 5, 12, 13);
            u[i + j + 2] = SNARESIM_SHUFFLE(t[i + j], t[i + j + 2], 2, 3, 10, 11, 6, 7, 14, 15);
        }
#pragma GCC unroll 4
    for (int j = 0; j < 4; ++j)
    {
        const Row low = SNARESIM_SHUFFLE(u[j], u[j + 4], 0, 1, 2, 3, 8, 9, 10, 11);
        const Row high = SNARESIM_SHUFFLE(u[j], u[j + 4], 4, 5, 6, 7, 12, 13, 14, 15);
        std::memcpy(tile + (size_t) ((j & 1) * 2 + (j >> 1)) * 8, &low, sizeof low);
        std::memcpy(tile + (size_t) ((j & 1) * 2 + (j >> 1) + 4) * 8, &high, sizeof high);
    }
#undef SNARESIM_SHUFFLE
}

// One run's taps (taps begin .. end - 1) over a block of up to 8 steps: each tap's source row
// holds its A at the block's steps, so the tap adds gain * A[b] to the run's sum at step b, whole
// rows, no gathers, kept by lane (the tap's place in the run modulo 8) and step, 8 rows of sums
// in registers; the taps of a lane add in their order. Into tile[b 8 + lane]. With Next, the
// gains `next` at once, from the same rows, into tileNext (16 rows of sums: wide targets only).
template <bool Next>
void sumRun(int begin, int end, const int* __restrict cell, const float* __restrict gain, const float* __restrict next,
            const float* __restrict rows, float* __restrict tile, float* __restrict tileNext)
{
    using Row = TapRow;
    Row s[8] = {}, x[8] = {}; // s[lane][step]
    int c = begin;
    for (; c + 8 <= end; c += 8)
    {
#pragma GCC unroll 8
        for (int lane = 0; lane < 8; ++lane)
        {
            Row a;
            std::memcpy(&a, rows + (size_t) cell[c + lane] * 8, sizeof a);
            s[lane] += gain[c + lane] * a;
            if constexpr (Next)
                x[lane] += next[c + lane] * a;
        }
    }
#pragma GCC unroll 8
    for (int lane = 0; lane < 8; ++lane) // the last round's (a constant lane keeps the sums in registers)
        if (c + lane < end)
        {
            Row a;
            std::memcpy(&a, rows + (size_t) cell[c + lane] * 8, sizeof a);
            s[lane] += gain[c + lane] * a;
            if constexpr (Next)
                x[lane] += next[c + lane] * a;
        }
    storeTransposed(s, tile);
    if constexpr (Next)
        storeTransposed(x, tileNext);
}

// A microphone's runs first .. last - 1 (a run per whole delay d; the taps before the first
// run's end at runEnd[first - 1]) over a block of up to Lanes (8) steps (the steps beyond the
// block are summed too, and not added: addTapTiles): each tap adds now * A[b] to its run's sum
// at step b and next * A[b] to the one a sample later, into the tiles
// tile[((d - first) Lanes + b) Lanes + lane], for addTapTiles.
template <int Lanes>
void sumTapBlock(int first, int last, const int* __restrict runEnd, const int* __restrict cell, const float* __restrict now,
                 const float* __restrict next, const float* __restrict rows, float* __restrict tileNow, float* __restrict tileNext)
{
    static_assert(Lanes == 8, "sumRun's rows are 8 floats");
    int t = first > 0 ? runEnd[first - 1] : 0;
    for (int d = first; d < last; ++d)
    {
        const int end = runEnd[d];
        float* n = tileNow + (size_t) (d - first) * Lanes * Lanes;
        float* x = tileNext + (size_t) (d - first) * Lanes * Lanes;
#if SNARESIM_VECTOR_BYTES >= 64 // 32 vector registers: both gains' sums in one pass over the rows
        sumRun<true>(t, end, cell, now, next, rows, n, x);
#else
        sumRun<false>(t, end, cell, now, nullptr, rows, n, nullptr);
        sumRun<false>(t, end, cell, next, nullptr, rows, x, nullptr);
#endif
        t = end;
    }
}

// The tiles of the block's steps from .. to - 1 into the ring (Lanes floats a sample; slot: the
// block's first step's ring slot plus the first run's delay): step by step, and in each step
// run by run, the run's sums at its delay and the ones of `next` at the sample after, lane by
// lane: the order the samples would get them step by step, so the sound does not depend on
// where the blocks fall.
template <int Lanes>
void addTapTiles(int delays, int from, int to, const float* __restrict tileNow, const float* __restrict tileNext, float* __restrict ring,
                 size_t slot, size_t mask)
{
    for (int b = from; b < to; ++b)
        for (int d = 0; d < delays; ++d)
        {
            const size_t at = slot + (size_t) b + (size_t) d;
            float* r0 = ring + (at & mask) * Lanes;
            float* r1 = ring + ((at + 1) & mask) * Lanes;
            const float* n = tileNow + ((size_t) d * Lanes + (size_t) b) * Lanes;
            const float* x = tileNext + ((size_t) d * Lanes + (size_t) b) * Lanes;
#pragma omp simd
            for (int lane = 0; lane < Lanes; ++lane)
                r0[lane] += n[lane];
#pragma omp simd
            for (int lane = 0; lane < Lanes; ++lane)
                r1[lane] += x[lane];
        }
}

// The cells' A^n = (V^{n+1} - 2 V^n + V^{n-1}) / k^2 from their blocks' sums at n+1 (V = scale
// times the sum: h^2 and the outward sign) into their rows (a cell's every Lanes-th float), the
// volumes moved on a step; returns the whole head's A^n.
template <int Lanes>
double cellAccelerations(int cells, const int* __restrict block, const double* __restrict blockSum, double scale, double inverseKk,
                         double* __restrict vNow, double* __restrict vPrev, float* __restrict rows)
{
    double whole = 0.0;
#pragma omp simd reduction(+ : whole)
    for (int j = 0; j < cells; ++j)
    {
        const double v = scale * blockSum[block[j]];
        const double a = (v - 2.0 * vNow[j] + vPrev[j]) * inverseKk; // A^n
        vPrev[j] = vNow[j];
        vNow[j] = v;
        rows[(size_t) j * Lanes] = (float) a;
        whole += a;
    }
    return whole;
}
