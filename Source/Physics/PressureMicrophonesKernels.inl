// The microphones' per-step loops (the cells' volume accelerations and the taps' sums),
// compiled once per vector target by PerVectorTarget.inl: no include guard, no includes.

// A microphone's runs of taps, a run per whole delay d from `slot`: now * A[cell] summed into
// ring sample slot + d and next * A[cell] into the one after, lane by lane (Lanes floats a
// sample). Each run holds whole vectors of Lanes taps (padded): a vector at a time (gathers),
// no sum across the lanes here.
template <int Lanes>
void sumTapRuns(int delays, const int* __restrict runEnd, const int* __restrict cell, const float* __restrict now,
                const float* __restrict next, const float* __restrict A, float* __restrict ring, size_t slot, size_t mask)
{
    int t = 0;
    for (int d = 0; d < delays; ++d, ++slot)
    {
        float s0[Lanes] = {}, s1[Lanes] = {};
        for (const int end = runEnd[d]; t < end; t += Lanes)
        {
#pragma omp simd
            for (int j = 0; j < Lanes; ++j)
            {
                const float a = A[cell[t + j]];
                s0[j] += now[t + j] * a;
                s1[j] += next[t + j] * a;
            }
        }
        float* r0 = ring + (slot & mask) * Lanes;
        float* r1 = ring + ((slot + 1) & mask) * Lanes;
#pragma omp simd
        for (int j = 0; j < Lanes; ++j)
        {
            r0[j] += s0[j];
            r1[j] += s1[j];
        }
    }
}

// The cells' A^n = (V^{n+1} - 2 V^n + V^{n-1}) / k^2 from their blocks' sums at n+1 (V = scale
// times the sum: h^2 and the outward sign), the volumes moved on a step; returns the whole
// head's A^n.
double cellAccelerations(int cells, const int* __restrict block, const double* __restrict blockSum, double scale, double inverseKk,
                         double* __restrict vNow, double* __restrict vPrev, double* __restrict accel)
{
    double whole = 0.0;
#pragma omp simd reduction(+ : whole)
    for (int j = 0; j < cells; ++j)
    {
        const double v = scale * blockSum[block[j]];
        const double a = (v - 2.0 * vNow[j] + vPrev[j]) * inverseKk; // A^n
        vPrev[j] = vNow[j];
        vNow[j] = v;
        accel[j] = a;
        whole += a;
    }
    return whole;
}
