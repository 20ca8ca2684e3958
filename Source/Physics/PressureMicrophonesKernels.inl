// The microphones' loops (the cells' volume accelerations each step, the taps' sums each block),
// compiled once per vector target by PerVectorTarget.inl: no include guard, no includes.

// A microphone's taps over a block of up to Lanes steps, a run per whole delay d: each tap's
// source row holds its A at the block's steps (b = 0 .. Lanes - 1, zero beyond the block), so
// now * A[b] goes to ring sample slot + d + b and next * A[b] to the one after: whole rows, no
// gathers; the run's rows summed in registers and added to the ring once.
template <int Lanes>
void sumTapBlock(int delays, const int* __restrict runEnd, const int* __restrict cell, const float* __restrict now,
                 const float* __restrict next, const float* __restrict rows, float* __restrict ring, size_t slot, size_t mask)
{
    int t = 0;
    for (int d = 0; d < delays; ++d, ++slot)
    {
        float s0[Lanes] = {}, s1[Lanes] = {}, u0[Lanes] = {}, u1[Lanes] = {};
        const int end = runEnd[d];
        for (; t + 1 < end; t += 2) // two taps at a time: two chains of sums
        {
            const float* a = rows + (size_t) cell[t] * Lanes;
            const float* b = rows + (size_t) cell[t + 1] * Lanes;
            const float n0 = now[t], x0 = next[t], n1 = now[t + 1], x1 = next[t + 1];
#pragma omp simd
            for (int j = 0; j < Lanes; ++j)
            {
                s0[j] += n0 * a[j];
                s1[j] += x0 * a[j];
                u0[j] += n1 * b[j];
                u1[j] += x1 * b[j];
            }
        }
        if (t < end)
        {
            const float* a = rows + (size_t) cell[t] * Lanes;
            const float n0 = now[t], x0 = next[t];
#pragma omp simd
            for (int j = 0; j < Lanes; ++j)
            {
                s0[j] += n0 * a[j];
                s1[j] += x0 * a[j];
            }
            ++t;
        }
        for (int j = 0; j < Lanes; ++j)
        {
            ring[(slot + (size_t) j) & mask] += s0[j] + u0[j];
            ring[(slot + (size_t) j + 1) & mask] += s1[j] + u1[j];
        }
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
