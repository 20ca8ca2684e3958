// The microphones' loops (the cells' volume accelerations each step, the taps' sums each block),
// compiled once per vector target by PerVectorTarget.inl: no include guard, no includes.

// A microphone's taps over a block of up to Lanes steps, a run per whole delay d: each tap's
// source row holds its A at the block's steps (b = 0 .. Lanes - 1; the steps beyond the block
// are summed too, and not added: addTapTiles), so a tap adds now * A[b] and next * A[b] to its
// run's sums at step b, whole rows, no gathers. Each
// run's sums are kept by lane (the tap's place in the run modulo Lanes) and step, into the
// tiles tile[(d Lanes + b) Lanes + lane], for addTapTiles.
template <int Lanes>
void sumTapBlock(int delays, const int* __restrict runEnd, const int* __restrict cell, const float* __restrict now,
                 const float* __restrict next, const float* __restrict rows, float* __restrict tileNow, float* __restrict tileNext)
{
    int t = 0;
    for (int d = 0; d < delays; ++d)
    {
        float sn[Lanes][Lanes] = {}, sx[Lanes][Lanes] = {}; // [lane][step]
        const int end = runEnd[d];
        for (int c = t; c < end; c += Lanes)
            for (int lane = 0; lane < Lanes && c + lane < end; ++lane)
            {
                const float* a = rows + (size_t) cell[c + lane] * Lanes;
                const float n = now[c + lane], x = next[c + lane];
#pragma omp simd
                for (int b = 0; b < Lanes; ++b)
                {
                    sn[lane][b] += n * a[b];
                    sx[lane][b] += x * a[b];
                }
            }
        t = end;
        float* tn = tileNow + (size_t) d * Lanes * Lanes;
        float* tx = tileNext + (size_t) d * Lanes * Lanes;
        for (int b = 0; b < Lanes; ++b)
            for (int lane = 0; lane < Lanes; ++lane)
            {
                tn[b * Lanes + lane] = sn[lane][b];
                tx[b * Lanes + lane] = sx[lane][b];
            }
    }
}

// The tiles of the block's `steps` steps into the ring (Lanes floats a sample): step by step,
// and in each step run by run, the run's sums at its delay and the ones of `next` at the sample
// after, lane by lane: the order the samples would get them step by step, so the sound does not
// depend on where the blocks fall.
template <int Lanes>
void addTapTiles(int delays, int steps, const float* __restrict tileNow, const float* __restrict tileNext, float* __restrict ring,
                 size_t slot, size_t mask)
{
    for (int b = 0; b < steps; ++b)
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
