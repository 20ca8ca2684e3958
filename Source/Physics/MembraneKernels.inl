// The membrane's hot loops (eq. 22 and what the couplings read and write on the grid),
// compiled once per vector target by PerVectorTarget.inl: no include guard, no includes.

// Eq. (22) (the carry head's (23) alike) over the disc's rows 1 .. n-2, row iy holding the nodes
// rowBegin[iy] .. rowEnd[iy] - 1, all inside the disc: out = c0 w + c1 (4 neighbours of w) + d0 wp
// + d1 (4 neighbours of wp) + push (+ px xs[m] + py y with Tilt, + field[m] with Field). With
// Sums, returns the sum of out, and with Tilt sets sx, sy to sum(xs out), sum(y out) (ys: y by
// row); without, returns 0 (the sums taken later). A vector of nodes at a time along each row; a
// row's last vector ends at the row's end, over the one before (out is written twice with the
// same values there, and its lanes already summed count nothing), so only rows shorter than a
// vector go node by node. The sums stay in vector lanes over every row and are added across the
// lanes once, at the end (no row's own sum is formed).
template <bool Sums, bool Tilt, bool Field>
double updateRows(double* __restrict out, const double* __restrict w, const double* __restrict wp, const double* __restrict field,
                  const double* __restrict xs, const double* __restrict ys, const int* __restrict rowBegin, const int* __restrict rowEnd,
                  int n, double c0, double c1, double d0, double d1, double push, double px, double py, double& sx, double& sy)
{
    constexpr int lanes = SNARESIM_VECTOR_BYTES / (int) sizeof(double);
    using V = double __attribute__((vector_size(SNARESIM_VECTOR_BYTES)));
    V vs = {}, vx = {}, vy = {};
    double ts = 0.0, tx = 0.0, ty = 0.0;
    V lane {};
    for (int i = 0; i < lanes; ++i)
        lane[i] = (double) i;
    const auto at = [&](int m, double p, V& x) {
        V c, l, r, u, d, cp, lp, rp, up, dp, next;
        std::memcpy(&c, w + m, sizeof c);
        std::memcpy(&l, w + m - 1, sizeof l);
        std::memcpy(&r, w + m + 1, sizeof r);
        std::memcpy(&u, w + m - n, sizeof u);
        std::memcpy(&d, w + m + n, sizeof d);
        std::memcpy(&cp, wp + m, sizeof cp);
        std::memcpy(&lp, wp + m - 1, sizeof lp);
        std::memcpy(&rp, wp + m + 1, sizeof rp);
        std::memcpy(&up, wp + m - n, sizeof up);
        std::memcpy(&dp, wp + m + n, sizeof dp);
        const V nb = l + r + u + d;
        const V nbp = lp + rp + up + dp;
        if constexpr (Tilt)
        {
            std::memcpy(&x, xs + m, sizeof x);
            next = c0 * c + c1 * nb + d0 * cp + d1 * nbp + (p + px * x);
        }
        else
            next = c0 * c + c1 * nb + d0 * cp + d1 * nbp + p;
        if constexpr (Field)
        {
            V f;
            std::memcpy(&f, field + m, sizeof f);
            next += f;
        }
        std::memcpy(out + m, &next, sizeof next);
        return next;
    };
    for (int iy = 1; iy < n - 1; ++iy)
    {
        const int begin = iy * n + rowBegin[iy], end = iy * n + rowEnd[iy];
        const double y = ys[iy];
        const double p = Tilt ? push + py * y : push;
        int m = begin;
        V x {};
        for (; m + lanes <= end; m += lanes)
        {
            const V next = at(m, p, x);
            if constexpr (Sums)
            {
                vs += next;
                if constexpr (Tilt)
                {
                    vx += x * next;
                    vy += y * next;
                }
            }
        }
        if (m == end)
            continue;
        if (end - begin >= lanes) // the last vector, over the one before
        {
            const int last = end - lanes;
            [[maybe_unused]] const V written = at(last, p, x);
            if constexpr (Sums)
            {
                const V keep = __builtin_convertvector(-(lane >= (double) (m - last)), V); // 1 for the lanes not summed yet
                const V next = written * keep;
                vs += next;
                if constexpr (Tilt)
                {
                    vx += x * next;
                    vy += y * next;
                }
            }
            continue;
        }
        for (; m < end; ++m)
        {
            const double nb = w[m - 1] + w[m + 1] + w[m - n] + w[m + n];
            const double nbp = wp[m - 1] + wp[m + 1] + wp[m - n] + wp[m + n];
            double next;
            if constexpr (Tilt)
                next = c0 * w[m] + c1 * nb + d0 * wp[m] + d1 * nbp + (p + px * xs[m]);
            else
                next = c0 * w[m] + c1 * nb + d0 * wp[m] + d1 * nbp + p;
            if constexpr (Field)
                next += field[m];
            out[m] = next;
            if constexpr (Sums)
            {
                ts += next;
                if constexpr (Tilt)
                {
                    tx += xs[m] * next;
                    ty += y * next;
                }
            }
        }
    }
    for (int i = 0; i < lanes; ++i)
    {
        ts += vs[i];
        tx += vx[i];
        ty += vy[i];
    }
    sx = tx;
    sy = ty;
    return ts;
}

// Eq. (22) in single precision over the whole padded grid, row after row without a break
// (nodes on and outside the rim are multiplied by the mask, so they stay zero), its sums on the
// way (a head whose sums are taken later: updateRowsFloat). Written as an increment,
// w+ = w + r v + cl L w + cs L v with v = w - w- and L the unscaled 5-point Laplacian, so that no
// coefficient near 2 multiplies w: a float coefficient's rounding then moves the modes by parts
// in 1e8 of their small restoring term, not of 2 w. Returns the sum of out, in double. With
// Tilt, a pressure px x + py y is added (xs, ys: x and y times the mask), and sx, sy are set to
// sum(xs out), sum(ys out) in double; with Field, a push per node (field, times the mask).
template <bool Tilt, bool Field>
double updateGridFloat(float* __restrict out, const float* __restrict w, const float* __restrict wp, const float* __restrict mask,
                       const float* __restrict xs, const float* __restrict ys, const float* __restrict field, int n, int count, float r,
                       float cl, float cs, float push, float px, float py, double& sx, double& sy)
{
    double sum = 0.0, ax = 0.0, ay = 0.0; // summed on the way, in double (vector lanes: the order is not the rows')
#pragma omp simd reduction(+ : sum, ax, ay)
    for (int m = 0; m < count; ++m)
    {
        const float c = w[m], v = c - wp[m];
        const float nb = w[m - 1] + w[m + 1] + w[m - n] + w[m + n];
        const float nbp = wp[m - 1] + wp[m + 1] + wp[m - n] + wp[m + n];
        float p = push;
        if constexpr (Field)
            p += field[m];
        float next;
        if constexpr (Tilt)
            next = mask[m] * (c + (r * v + cl * (nb - 4.0f * c) + cs * ((nb - nbp) - 4.0f * v) + p)) + (px * xs[m] + py * ys[m]);
        else
            next = mask[m] * (c + (r * v + cl * (nb - 4.0f * c) + cs * ((nb - nbp) - 4.0f * v) + p));
        out[m] = next;
        sum += (double) next;
        if constexpr (Tilt)
        {
            ax += (double) xs[m] * (double) next;
            ay += (double) ys[m] * (double) next;
        }
    }
    sx = ax;
    sy = ay;
    return sum;
}
// updateGridFloat's eq. (22) (its sums taken later) row by row over the disc's nodes only: row
// iy's nodes rowBegin[iy] .. rowEnd[iy] - 1, a vector at a time, the row's last vector ending at
// its end over the one before (out is written twice with the same values there). A row shorter
// than a vector takes one vector whose lanes beyond the row write zero (nodes off the disc). No
// mask is read, and with Tilt the pressure px x + py y takes x by column (xAxis) and y by row
// (yAxis): the same values, in the same operations, as updateGridFloat's inside the disc.
template <bool Tilt, bool Field>
void updateRowsFloat(float* __restrict out, const float* __restrict w, const float* __restrict wp, const float* __restrict xAxis,
                     const float* __restrict yAxis, const float* __restrict field, const int* __restrict rowBegin,
                     const int* __restrict rowEnd, int n, float r, float cl, float cs, float push, float px, float py)
{
    constexpr int lanes = SNARESIM_VECTOR_BYTES / (int) sizeof(float);
    using V = float __attribute__((vector_size(SNARESIM_VECTOR_BYTES)));
    V lane {};
    for (int i = 0; i < lanes; ++i)
        lane[i] = (float) i;
    for (int iy = 1; iy < n - 1; ++iy)
    {
        const int row = iy * n, begin = rowBegin[iy], end = rowEnd[iy];
        if (begin >= end)
            continue;
        const float tiltY = Tilt ? py * yAxis[iy] : 0.0f;
        const auto at = [&](int ix) {
            const int m = row + ix;
            V c, l, rt, u, d, cp, lp, rp, up, dp;
            std::memcpy(&c, w + m, sizeof c);
            std::memcpy(&l, w + m - 1, sizeof l);
            std::memcpy(&rt, w + m + 1, sizeof rt);
            std::memcpy(&u, w + m - n, sizeof u);
            std::memcpy(&d, w + m + n, sizeof d);
            std::memcpy(&cp, wp + m, sizeof cp);
            std::memcpy(&lp, wp + m - 1, sizeof lp);
            std::memcpy(&rp, wp + m + 1, sizeof rp);
            std::memcpy(&up, wp + m - n, sizeof up);
            std::memcpy(&dp, wp + m + n, sizeof dp);
            const V v = c - cp, nb = (l + rt) + u + d, nbp = (lp + rp) + up + dp;
            V p = V {} + push;
            if constexpr (Field)
            {
                V f;
                std::memcpy(&f, field + m, sizeof f);
                p += f;
            }
            V next = c + (r * v + cl * (nb - 4.0f * c) + cs * ((nb - nbp) - 4.0f * v) + p);
            if constexpr (Tilt)
            {
                V x;
                std::memcpy(&x, xAxis + ix, sizeof x);
                next += px * x + tiltY;
            }
            return next;
        };
        if (end - begin >= lanes)
        {
            int ix = begin;
            for (; ix + lanes <= end; ix += lanes)
            {
                const V next = at(ix);
                std::memcpy(out + row + ix, &next, sizeof next);
            }
            if (ix < end)
            {
                const V next = at(end - lanes);
                std::memcpy(out + row + end - lanes, &next, sizeof next);
            }
        }
        else if (lanes <= n - 2) // one vector inside the padded row, zero off the disc
        {
            const int start = std::min(begin, n - 1 - lanes);
            const V ix = lane + (float) start;
            const V keep = __builtin_convertvector(-((ix >= (float) begin) & (ix < (float) end)), V); // 1 on the disc, else 0
            const V next = at(start) * keep;
            std::memcpy(out + row + start, &next, sizeof next);
        }
        else // a grid narrower than a vector: node by node
            for (int ix = begin; ix < end; ++ix)
            {
                const int m = row + ix;
                const float c = w[m], v = c - wp[m];
                const float nb = (w[m - 1] + w[m + 1]) + w[m - n] + w[m + n];
                const float nbp = (wp[m - 1] + wp[m + 1]) + wp[m - n] + wp[m + n];
                float p = push;
                if constexpr (Field)
                    p += field[m];
                float next = c + (r * v + cl * (nb - 4.0f * c) + cs * ((nb - nbp) - 4.0f * v) + p);
                if constexpr (Tilt)
                    next += px * xAxis[ix] + tiltY;
                out[m] = next;
            }
    }
}
// sum(xs w), sum(ys w) over count nodes, in double (vector lanes).
template <class Real>
void firstMoments(const Real* __restrict w, const Real* __restrict xs, const Real* __restrict ys, int count, double& sx, double& sy)
{
    double ax = 0.0, ay = 0.0;
#pragma omp simd reduction(+ : ax, ay)
    for (int m = 0; m < count; ++m)
    {
        const double wm = (double) w[m];
        ax += (double) xs[m] * wm;
        ay += (double) ys[m] * wm;
    }
    sx = ax;
    sy = ay;
}
// Block sums of an n x n grid (block (bx, by): the nodes with ix / side == bx, iy / side == by)
// with the grid's sum and, with Moments, its first moments on the way, in double whatever the
// state (the microphones take second differences in time of these sums, which would lift a float
// sum's rounding by 1 / (omega k)^2): every band's rows summed node by node into a row of acc
// (zero beyond n), then each row's runs of side values, a block each, read once every band is
// summed (a load over stores still in flight waits for them); acc holds every band's row. The
// moments weight each node by its row's y (ys, by row) and each band's column sum by its
// column's x (xs, by column). Explicit vectors along the rows, the last one ending at n over the
// one before (its lanes summed already count nothing twice: a weight of 0 or 1 each), so no row
// has a scalar end; the sums stay in vector lanes to the end. Rows: the band's rows, a constant
// where it is Side (0: any, `rows`).
using DoubleVector = double __attribute__((vector_size(SNARESIM_VECTOR_BYTES)));
using DoubleVectorFloats = float __attribute__((vector_size(SNARESIM_VECTOR_BYTES / 2))); // a DoubleVector's lanes in float
// A DoubleVector's lanes of floats at p, widened: one conversion from memory on the wide
// targets (GCC splits __builtin_convertvector there into halves and reassembles them); of
// doubles, loaded.
inline DoubleVector lanesInDouble(const float* p)
{
#if SNARESIM_VECTOR_TARGETS && SNARESIM_VECTOR_BYTES == 64
    return (DoubleVector) _mm512_maskz_cvtps_pd((__mmask8) -1, _mm256_loadu_ps(p)); // _mm512_cvtps_pd: a false GCC 12 warning
#elif SNARESIM_VECTOR_TARGETS && SNARESIM_VECTOR_BYTES == 32
    return (DoubleVector) _mm256_cvtps_pd(_mm_loadu_ps(p));
#else
    DoubleVectorFloats r;
    std::memcpy(&r, p, sizeof r);
    return __builtin_convertvector(r, DoubleVector);
#endif
}
inline DoubleVector lanesInDouble(const double* p)
{
    DoubleVector r;
    std::memcpy(&r, p, sizeof r);
    return r;
}
template <int Rows, bool Moments, class Real>
void sumBand(const Real* __restrict row0, int n, int rows, const double* __restrict xs, const double* __restrict y,
             double* __restrict band, DoubleVector& total, DoubleVector& sx, DoubleVector& sy)
{
    constexpr int lanes = SNARESIM_VECTOR_BYTES / (int) sizeof(double);
    using V = DoubleVector;
    const int count = Rows > 0 ? Rows : rows;
    for (int start = 0; start < n; start += lanes)
    {
        const int ix = std::min(start, n - lanes);
        V v = lanesInDouble(row0 + (size_t) ix), b = v, t = y[0] * v;
        for (int k = 1; k < count; ++k)
        {
            v = lanesInDouble(row0 + (size_t) k * (size_t) n + (size_t) ix);
            b += v;
            t += y[k] * v;
        }
        std::memcpy(band + ix, &b, sizeof b);
        if (ix < start) // the lanes before `start` are summed already
        {
            V keep;
            for (int i = 0; i < lanes; ++i)
                keep[i] = ix + i >= start ? 1.0 : 0.0;
            b *= keep;
            if constexpr (Moments)
                t *= keep;
        }
        total += b;
        if constexpr (Moments)
        {
            V x;
            std::memcpy(&x, xs + ix, sizeof x);
            sx += x * b;
            sy += t;
        }
    }
}
template <int Side, bool Moments, class Real>
void sumBlocksAndMoments(const Real* __restrict w, int n, int side, const double* __restrict xs, const double* __restrict ys,
                         double* __restrict acc, double* __restrict out, double& sum, double& sx, double& sy)
{
    constexpr int lanes = SNARESIM_VECTOR_BYTES / (int) sizeof(double);
    const int s = Side > 0 ? Side : side, blocks = (n + s - 1) / s, length = blocks * s;
    DoubleVector vt {}, vx {}, vy {};
    for (int by = 0; by < blocks; ++by)
    {
        const int first = by * s, rows = std::min(n, first + s) - first;
        const Real* row0 = w + (size_t) first * (size_t) n;
        double* band = acc + (size_t) by * (size_t) length;
        if (n < lanes) // not a head's grid
            for (int ix = 0; ix < n; ++ix)
            {
                double b = 0.0, t = 0.0;
                for (int r = 0; r < rows; ++r)
                {
                    const double v = (double) row0[(size_t) r * (size_t) n + (size_t) ix];
                    b += v;
                    t += ys[first + r] * v;
                }
                band[ix] = b;
                vt[0] += b;
                vx[0] += xs[ix] * b;
                vy[0] += t;
            }
        else if (Side > 0 && rows == Side)
            sumBand<Side, Moments>(row0, n, rows, xs, ys + first, band, vt, vx, vy);
        else
            sumBand<0, Moments>(row0, n, rows, xs, ys + first, band, vt, vx, vy);
        for (int ix = n; ix < length; ++ix)
            band[ix] = 0.0;
    }
    for (int by = 0; by < blocks; ++by)
    {
        const double* band = acc + (size_t) by * (size_t) length;
        double* o = out + (size_t) by * (size_t) blocks;
        for (int bx = 0; bx < blocks; ++bx)
        {
            double b = band[bx * s];
            for (int c = 1; c < s; ++c)
                b += band[bx * s + c];
            o[bx] = b;
        }
    }
    double total = 0.0, ax = 0.0, ay = 0.0;
    for (int i = 0; i < lanes; ++i)
    {
        total += vt[i];
        ax += vx[i];
        ay += vy[i];
    }
    sum = total;
    sx = Moments ? ax : 0.0;
    sy = Moments ? ay : 0.0;
}
template <bool Moments, class Real>
void blockSumsAndMoments(const Real* w, int n, int side, const double* xs, const double* ys, double* acc, double* out, double& sum,
                         double& sx, double& sy)
{
    // sides up to 8 nodes as constants, so that a band's rows unroll (the microphones' 20 mm cells
    // are 1 to 5 nodes a side at every bandwidth); any other side as a variable
    switch (side)
    {
        case 1: sumBlocksAndMoments<1, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        case 2: sumBlocksAndMoments<2, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        case 3: sumBlocksAndMoments<3, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        case 4: sumBlocksAndMoments<4, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        case 5: sumBlocksAndMoments<5, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        case 6: sumBlocksAndMoments<6, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        case 7: sumBlocksAndMoments<7, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        case 8: sumBlocksAndMoments<8, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy); return;
        default: break;
    }
    sumBlocksAndMoments<0, Moments>(w, n, side, xs, ys, acc, out, sum, sx, sy);
}
// The rectangle's second differences in time summed over blocks of side x side nodes (side 2
// and up; Side: a constant side, 0: `side`), in double: every band of side rows into its row of
// acc, each column's sum in row order (a vector of columns at a time, the band's rows unrolled
// for a constant side; the last vector ends at the rectangle's edge over the one before and
// stores the same values), then each band's runs of side columns, read once every band is summed
// (as sumBlocksAndMoments). acc holds ceil(rows / side) rows of `columns`. Block b's sum s goes to
// out[b * stride] as the float (s hh) scale.
template <int Side, class Real>
void bandSecondDifferences(const Real* __restrict next, const Real* __restrict now, const Real* __restrict prev, int n, int ix0, int iy0,
                           int columns, int rows, int side, double hh, double scale, double* __restrict acc, float* __restrict out,
                           int stride)
{
    constexpr int lanes = SNARESIM_VECTOR_BYTES / (int) sizeof(double);
    using V = DoubleVector;
    const int s = Side > 0 ? Side : side, bxs = (columns + s - 1) / s, bys = (rows + s - 1) / s;
    const auto at = [&](int iy, int ix) { return (size_t) iy * (size_t) n + (size_t) (ix0 + ix); };
    for (int by = 0; by < bys; ++by)
    {
        const int first = iy0 + by * s, count = std::min(rows - by * s, s);
        double* band = acc + (size_t) by * (size_t) columns;
        if (columns < lanes) // narrower than a vector: column by column
        {
            for (int ix = 0; ix < columns; ++ix)
            {
                double b = 0.0;
                for (int r = 0; r < count; ++r)
                {
                    const size_t o = at(first + r, ix);
                    b += ((double) next[o] - 2.0 * (double) now[o]) + (double) prev[o];
                }
                band[ix] = b;
            }
            continue;
        }
        for (int start = 0; start < columns; start += lanes)
        {
            const int ix = std::min(start, columns - lanes);
            V b {};
            const auto add = [&](int iy) {
                const size_t o = at(iy, ix);
                b += (lanesInDouble(next + o) - 2.0 * lanesInDouble(now + o)) + lanesInDouble(prev + o);
            };
            if (Side > 0 && count == Side)
                for (int r = 0; r < Side; ++r)
                    add(first + r);
            else
                for (int r = 0; r < count; ++r)
                    add(first + r);
            std::memcpy(band + ix, &b, sizeof b);
        }
    }
    for (int by = 0; by < bys; ++by)
    {
        const double* band = acc + (size_t) by * (size_t) columns;
        float* o = out + (size_t) by * (size_t) bxs * (size_t) stride;
        const int whole = columns / s; // the blocks of s columns
        for (int bx = 0; bx < whole; ++bx)
        {
            double sum = 0.0;
            for (int c = 0; c < s; ++c)
                sum += band[bx * s + c];
            o[(size_t) bx * (size_t) stride] = (float) ((sum * hh) * scale);
        }
        if (whole < bxs)
        {
            double sum = 0.0;
            for (int ix = whole * s; ix < columns; ++ix)
                sum += band[ix];
            o[(size_t) whole * (size_t) stride] = (float) ((sum * hh) * scale);
        }
    }
}
// The rectangle's second differences in time summed over blocks of side x side nodes, scaled
// into every stride-th float of out: a block a node (side 1) directly; larger blocks by
// bandSecondDifferences, the fine cells' sides 2 and 3 (the microphones' 8 mm cells on grids
// finer than 5.3 mm) as constants.
template <class Real>
void blockSecondDifferences(const Real* __restrict next, const Real* __restrict now, const Real* __restrict prev, int n, int ix0, int iy0,
                            int columns, int rows, int side, double hh, double scale, double* __restrict acc, float* __restrict out,
                            int stride)
{
    if (side == 1) // a block a node
    {
        for (int iy = 0; iy < rows; ++iy)
        {
            const size_t o = (size_t) (iy0 + iy) * (size_t) n + (size_t) ix0;
            float* row = out + (size_t) iy * (size_t) columns * (size_t) stride;
            for (int ix = 0; ix < columns; ++ix)
            {
                const double s = ((double) next[o + ix] - 2.0 * (double) now[o + ix]) + (double) prev[o + ix];
                row[(size_t) ix * (size_t) stride] = (float) ((s * hh) * scale);
            }
        }
        return;
    }
    const auto bands = side == 2   ? bandSecondDifferences<2, Real>
                       : side == 3 ? bandSecondDifferences<3, Real>
                                   : bandSecondDifferences<0, Real>;
    bands(next, now, prev, n, ix0, iy0, columns, rows, side, hh, scale, acc, out, stride);
}
// w at count nodes into out (a gather).
template <class Real>
void gatherNodes(const Real* __restrict w, const int* __restrict nodes, double* __restrict out, int count)
{
#pragma omp simd
    for (int j = 0; j < count; ++j)
        out[j] = (double) w[nodes[j]];
}
// values[j] at node nodes[k] of w, k = index[j] (index null: j; the k distinct and increasing),
// a scatter. Each change is summed into one of four partial sums by k & 3, in the order of j:
// an entry k left out whose value is its node's own adds exactly zero, so any subset of the k
// gives the same sums to the last bit. Returns the change of w's sum; with Moments also adds the
// changes of sum(xs w), sum(ys w) to dx, dy.
template <bool Moments, class Real>
double scatterNodesKeyed(Real* __restrict w, const Real* __restrict xs, const Real* __restrict ys, const int* __restrict nodes,
                         const double* __restrict values, const int* __restrict index, int count, double& dx, double& dy)
{
    double c[4] = {}, cx[4] = {}, cy[4] = {};
    for (int j = 0; j < count; ++j)
    {
        const int k = index != nullptr ? index[j] : j, node = nodes[k], lane = k & 3;
        const Real v = (Real) values[j];
        const double d = (double) v - (double) w[node];
        c[lane] += d;
        if constexpr (Moments)
        {
            cx[lane] += (double) xs[node] * d;
            cy[lane] += (double) ys[node] * d;
        }
        w[node] = v;
    }
    if constexpr (Moments)
    {
        dx += (cx[0] + cx[1]) + (cx[2] + cx[3]);
        dy += (cy[0] + cy[1]) + (cy[2] + cy[3]);
    }
    return (c[0] + c[1]) + (c[2] + c[3]);
}

// out[ix] = scale * perBlock[block[ix]] along a row (a band's blocks, node by node).
template <class Real>
void expandRow(int n, const int* __restrict block, const double* __restrict perBlock, double scale, Real* __restrict out)
{
#pragma omp simd
    for (int ix = 0; ix < n; ++ix)
        out[ix] = (Real) (scale * perBlock[block[ix]]);
}
// A band's first row copied to its other rows.
template <class Real>
void copyRows(Real* band, int n, int rows)
{
    const Real* __restrict first = band;
    for (int r = 1; r < rows; ++r)
    {
        Real* __restrict row = band + (size_t) r * (size_t) n;
#pragma omp simd
        for (int ix = 0; ix < n; ++ix)
            row[ix] = first[ix];
    }
}
