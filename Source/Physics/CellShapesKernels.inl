// The shapes' sums over a head's cells (pressures from weights, projections of volumes),
// compiled once per vector target by PerVectorTarget.inl: no include guard, no includes.

template <class Real>
void combine(int shapes, int cells, const double* __restrict weight, const Real* __restrict shape, double* __restrict out)
{
    std::fill(out, out + cells, 0.0);
    int s = 0;
    for (; s + 4 <= shapes; s += 4)
    {
        const Real* __restrict a = shape + (size_t) s * (size_t) cells;
        const Real* __restrict b = a + cells;
        const Real* __restrict c = b + cells;
        const Real* __restrict d = c + cells;
        const double wa = weight[s], wb = weight[s + 1], wc = weight[s + 2], wd = weight[s + 3];
#pragma omp simd
        for (int i = 0; i < cells; ++i)
            out[i] += (wa * (double) a[i] + wb * (double) b[i]) + (wc * (double) c[i] + wd * (double) d[i]);
    }
    for (; s < shapes; ++s)
    {
        const Real* __restrict a = shape + (size_t) s * (size_t) cells;
        const double w = weight[s];
#pragma omp simd
        for (int i = 0; i < cells; ++i)
            out[i] += w * (double) a[i];
    }
}

template <class Real>
void project(int shapes, int cells, const Real* __restrict shape, const double* __restrict v, double scale, double* __restrict out)
{
    int s = 0;
    for (; s + 4 <= shapes; s += 4)
    {
        const Real* __restrict a = shape + (size_t) s * (size_t) cells;
        const Real* __restrict b = a + cells;
        const Real* __restrict c = b + cells;
        const Real* __restrict d = c + cells;
        double sa = 0.0, sb = 0.0, sc = 0.0, sd = 0.0;
#pragma omp simd reduction(+ : sa, sb, sc, sd)
        for (int i = 0; i < cells; ++i)
        {
            const double x = v[i];
            sa += (double) a[i] * x;
            sb += (double) b[i] * x;
            sc += (double) c[i] * x;
            sd += (double) d[i] * x;
        }
        out[s] = scale * sa;
        out[s + 1] = scale * sb;
        out[s + 2] = scale * sc;
        out[s + 3] = scale * sd;
    }
    for (; s < shapes; ++s)
    {
        const Real* __restrict a = shape + (size_t) s * (size_t) cells;
        double sum = 0.0;
#pragma omp simd reduction(+ : sum)
        for (int i = 0; i < cells; ++i)
            sum += (double) a[i] * v[i];
        out[s] = scale * sum;
    }
}
