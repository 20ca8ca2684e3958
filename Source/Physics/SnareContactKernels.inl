// The snare contact's per-point loops (the quadratised solve, eq. 48-50), compiled once per
// vector target by PerVectorTarget.inl: no include guard, no includes.

// The per-point coefficients of the quadratised solve for the Hertz exponent (beta = 1.5, so
// psi = psiScale xi^(5/4)), for `count` points whose groups' W0 and cc are W0[group[k]] and
// cc[group[k]], branch-free so that it vectorises. xi* = u* - W0 is the prediction (no contact
// force); g is the secant of psi from xi^{n-1} to xi*. While both touch, with x, y their fourth
// roots, it is (y^5 - x^5) / (y^4 - x^4) = (x^4 + x^3 y + x^2 y^2 + x y^3 + y^4) / ((x + y)(x^2 + y^2)):
// no difference of near values, down to the tangent (5/4) x when they meet.
// Damped: the contact's damping D = damping [xi^n]_+^(3/2) (lambda kappa xi^beta / (2k), Hunt and
// Crossley) adds D (xi^{n+1} - xi^{n-1}) to the force, so it joins B = g^2 / 4; into damp[k].
// g is taken in single precision: it may be any value without breaking the energy identity
// (SnareContact.h), so its rounding only perturbs the force law, by about 1e-7. Its loop is
// apart, in floats only, so that it runs twice the points a vector of the doubles holds;
// gapBefore, gapPredicted and spanSecant (count each) hold the gaps and the span in floats, then
// (spanSecant) the secant.
template <bool Damped>
void hertzCoefficients(int count, const int* __restrict wireNode, const double* __restrict xiPrev, const double* __restrict xiNow,
                       const double* __restrict u, const double* __restrict psi, const int* __restrict group, const double* __restrict W0,
                       const double* __restrict cc, double hs, double psiScale, double gammaS, double damping, double* __restrict gq,
                       double* __restrict alpha, double* __restrict beta, double* __restrict uFree, double* __restrict damp,
                       float* __restrict gapBefore, float* __restrict gapPredicted, float* __restrict spanSecant)
{
    // the gaps xi^{n-1} and xi* (0 where apart) and the span xi* - xi^{n-1}, kept in alpha meanwhile
    for (int k = 0; k < count; ++k)
    {
        const double a = xiPrev[k];
        const double us = u[wireNode[k]];
        const double b = us - W0[group[k]];
        const double span = b - a;
        gapBefore[k] = a > 0.0 ? (float) a : 0.0f;
        gapPredicted[k] = b > 0.0 ? (float) b : 0.0f;
        spanSecant[k] = span != 0.0 ? (float) span : 1.0f;
        alpha[k] = span;
        uFree[k] = us;
    }
    // the secant over psiScale
    for (int k = 0; k < count; ++k)
    {
        const float af = gapBefore[k], bf = gapPredicted[k];
        const float x = std::sqrt(std::sqrt(af)), y = std::sqrt(std::sqrt(bf));
        const float x2 = x * x, y2 = y * y;
        const bool both = (x > 0.0f) & (y > 0.0f);
        // at most one touching: (psi(b) - psi(a)) / (b - a), one of the two terms zero
        const float num = both ? (x2 * x2 + x * y * (x2 + y2) + x2 * y2) + y2 * y2 : bf * y - af * x;
        const float den = both ? (x + y) * (x2 + y2) : spanSecant[k];
        spanSecant[k] = num / den;
    }
    for (int k = 0; k < count; ++k)
    {
        const double g = psiScale * (double) spanSecant[k];
        double B = 0.25 * g * g;
        if constexpr (Damped)
        {
            const double now = xiNow[k] > 0.0 ? xiNow[k] : 0.0;
            const double D = damping * now * std::sqrt(now);
            damp[k] = D;
            B += D;
        }
        const double d = 1.0 / (1.0 + gammaS * B);
        gq[k] = g;
        alpha[k] = (g * psi[k] + B * alpha[k]) * d;
        beta[k] = cc[group[k]] * hs * B * d;
    }
}

// to[index[t]] = from[t] for count distinct indices (a scatter).
void scatterPoints(int count, const int* __restrict index, const double* __restrict from, double* __restrict to)
{
#pragma omp simd
    for (int t = 0; t < count; ++t)
        to[index[t]] = from[t];
}
// out[t] = scale * from[index[t]] (a gather).
void gatherScaled(int count, const int* __restrict index, const double* __restrict from, double scale, double* __restrict out)
{
#pragma omp simd
    for (int t = 0; t < count; ++t)
        out[t] = scale * from[index[t]];
}

// Per point, its group's S and W at S[group[k]] and W[group[k]]: the force
// f = alpha - beta S, the wire u = u* - gammaS f, the gap xi^{n+1} = u - W and psi at n+1/2;
// `dropped` gets psi^2 where psi is reset and, Damped, 2 / h_s times the energy the contact's
// damping took, damp[k] (xi^{n+1} - xi^{n-1})^2.
template <bool Damped>
void finishPoints(int count, const double* __restrict alpha, const double* __restrict beta, const double* __restrict gq,
                  const int* __restrict group, const double* __restrict S, const double* __restrict W, double gammaS,
                  const double* __restrict xiPrev, const double* __restrict xiNow, const double* __restrict damp, double* __restrict uFree,
                  double* __restrict xiNext, double* __restrict psi, double* __restrict dropped)
{
    for (int k = 0; k < count; ++k)
    {
        const double f = alpha[k] - beta[k] * S[group[k]];
        const double u = uFree[k] - gammaS * f;
        const double xiNew = u - W[group[k]];
        uFree[k] = u;
        xiNext[k] = xiNew;
        const double next = psi[k] + 0.5 * gq[k] * (xiNew - xiPrev[k]);
        // psi at n+1/2 stands for the potential of xi^n and xi^{n+1}: on the step a point leaves
        // the head it still holds what xi^n stored, and the next step gives that back as force.
        // Apart at n and n+1, what is left is psi's drift: reset, so the next contact starts
        // from zero.
        const bool keep = (xiNew > 0.0) | (xiNow[k] > 0.0);
        dropped[k] = keep ? 0.0 : next * next;
        if constexpr (Damped)
        {
            const double r = xiNew - xiPrev[k];
            dropped[k] += damp[k] * r * r;
        }
        psi[k] = keep ? next : 0.0;
    }
}
// One class of `count` groups of `size` points (member-major): per group S = sum alpha /
// (1 + sum beta), the node W = W0 + cc h_s S. The sums run member by member over the groups
// (contiguous, so they vectorise), each group's in member order; S and W hold them meanwhile.
void solveClass(int size, int count, const double* __restrict alpha, const double* __restrict beta, const double* __restrict W0,
                const double* __restrict cc, double hs, double* __restrict S, double* __restrict W)
{
    for (int i = 0; i < count; ++i)
        S[i] = W[i] = 0.0; // a class of size 0: nodes that hold wire ends only
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < count; ++i)
        {
            S[i] += alpha[j * count + i];
            W[i] += beta[j * count + i];
        }
    for (int i = 0; i < count; ++i)
    {
        S[i] = S[i] / (1.0 + W[i]);
        W[i] = W0[i] + cc[i] * hs * S[i];
    }
}

// solveClass over every class of a layout (its points' and groups' arrays whole).
void solveClasses(const SnareContact::SizeClass* classes, int numClasses, const double* __restrict alpha, const double* __restrict beta,
                  const double* __restrict W0, const double* __restrict cc, double hs, double* __restrict S, double* __restrict W)
{
    for (int c = 0; c < numClasses; ++c)
    {
        const SnareContact::SizeClass& k = classes[c];
        solveClass(k.size, k.groupCount, alpha + k.pointBegin, beta + k.pointBegin, W0 + k.groupBegin, cc + k.groupBegin, hs,
                   S + k.groupBegin, W + k.groupBegin);
    }
}

// Over all points: the sum of dropped, the largest gap (0 when all apart) and the number
// touching, four points at a time (GCC's vector extensions, so that it vectorises).
using Double4 = double __attribute__((vector_size(32)));
using Long4 = long long __attribute__((vector_size(32)));
double summarise(int n, const double* __restrict xi, const double* __restrict dropped, double& deepest, int& touching)
{
    Double4 sum = {}, top = {};
    Long4 count = {};
    int t = 0;
    for (; t + 4 <= n; t += 4)
    {
        Double4 x, d;
        std::memcpy(&x, xi + t, sizeof x);
        std::memcpy(&d, dropped + t, sizeof d);
        sum += d;
        top = top < x ? x : top;
        count -= x > 0.0; // true is -1
    }
    double total = (sum[0] + sum[1]) + (sum[2] + sum[3]);
    deepest = std::max(std::max(top[0], top[1]), std::max(top[2], top[3]));
    touching = (int) (count[0] + count[1] + count[2] + count[3]);
    for (; t < n; ++t)
    {
        total += dropped[t];
        deepest = std::max(deepest, xi[t]);
        touching += xi[t] > 0.0 ? 1 : 0;
    }
    return total;
}

// One class of `count` groups of `size` points (member-major), each group's W0 at W0[i]: per
// point the gap without contact forces, xi* = u* - W0, into xiNext (the gap of a point left out
// of the solve); per group the largest of its points' xi^{n-1}, xi* and |psi| into reach. A
// group whose reach is not positive has no point touching at n-1 or at xi* and none holding
// psi: each of its points has g = 0, no force and keeps psi = 0, so its solve leaves it as it is.
// A vector of groups at a time, its reach held over the members; the last vector ends at the
// class's end, over the one before (its groups' values written twice, the same).
void predictClass(int size, int count, const int* __restrict wireNode, const double* __restrict u, const double* __restrict W0,
                  const double* __restrict xiPrev, const double* __restrict psi, double* __restrict xiNext, double* __restrict reach)
{
    constexpr int lanes = SNARESIM_VECTOR_BYTES / (int) sizeof(double);
    using V = double __attribute__((vector_size(SNARESIM_VECTOR_BYTES)));
    const auto groupsFrom = [&](int i) {
        V w0, top {};
        std::memcpy(&w0, W0 + i, sizeof w0);
        for (int j = 0; j < size; ++j)
        {
            const int k = j * count + i;
            V us, prev, q;
            for (int l = 0; l < lanes; ++l)
                us[l] = u[wireNode[k + l]];
            const V b = us - w0;
            std::memcpy(xiNext + k, &b, sizeof b);
            std::memcpy(&prev, xiPrev + k, sizeof prev);
            std::memcpy(&q, psi + k, sizeof q);
            const V x = prev > b ? prev : b;
            const V p = q < 0.0 ? -q : q;
            const V r = x > p ? x : p;
            top = top > r ? top : r;
        }
        std::memcpy(reach + i, &top, sizeof top);
    };
    if (count >= lanes)
    {
        int i = 0;
        for (; i + lanes <= count; i += lanes)
            groupsFrom(i);
        if (i < count)
            groupsFrom(count - lanes);
        return;
    }
    for (int i = 0; i < count; ++i)
        reach[i] = 0.0;
    for (int j = 0; j < size; ++j)
        for (int i = 0; i < count; ++i)
        {
            const int k = j * count + i;
            const double b = u[wireNode[k]] - W0[i];
            xiNext[k] = b;
            const double x = xiPrev[k] > b ? xiPrev[k] : b;
            const double p = std::abs(psi[k]);
            const double r = x > p ? x : p;
            reach[i] = reach[i] > r ? reach[i] : r;
        }
}

// predictClass over every class of a layout (its points' and groups' arrays whole).
void predictClasses(const SnareContact::SizeClass* classes, int numClasses, const int* __restrict wireNode, const double* __restrict u,
                    const double* __restrict W0, const double* __restrict xiPrev, const double* __restrict psi, double* __restrict xiNext,
                    double* __restrict reach)
{
    for (int c = 0; c < numClasses; ++c)
    {
        const SnareContact::SizeClass& k = classes[c];
        predictClass(k.size, k.groupCount, wireNode + k.pointBegin, u, W0 + k.groupBegin, xiPrev + k.pointBegin, psi + k.pointBegin,
                     xiNext + k.pointBegin, reach + k.groupBegin);
    }
}

// The indices first + i of the `count` groups whose reach is positive, in order, into list;
// returns how many. On avx512 sixteen at a time, compressed in a register and stored whole; on
// avx2 four at a time, packed by a byte shuffle from a table of the sixteen masks and stored
// whole (the lanes beyond the count land where later groups' indices go: list holds count
// entries).
#if SNARESIM_VECTOR_TARGETS && SNARESIM_VECTOR_BYTES == 32
// For each mask of four lanes, the bytes that pack its set lanes' 32-bit values to the front.
struct PackTable
{
    alignas(16) signed char bytes[16][16];
    constexpr PackTable() : bytes {}
    {
        for (int mask = 0; mask < 16; ++mask)
        {
            int to = 0;
            for (int lane = 0; lane < 4; ++lane)
                if ((mask >> lane) & 1)
                {
                    for (int b = 0; b < 4; ++b)
                        bytes[mask][4 * to + b] = (signed char) (4 * lane + b);
                    ++to;
                }
            for (int b = 4 * to; b < 16; ++b)
                bytes[mask][b] = -1; // zero
        }
    }
};
inline constexpr PackTable packTable {};
#endif
int listReaching(int count, const double* __restrict reach, int first, int* __restrict list)
{
    int n = 0, i = 0;
#if SNARESIM_VECTOR_TARGETS && SNARESIM_VECTOR_BYTES == 32
    __m128i ids = _mm_add_epi32(_mm_set1_epi32(first), _mm_setr_epi32(0, 1, 2, 3));
    for (; i + 4 <= count; i += 4)
    {
        const int taking = _mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(reach + i), _mm256_setzero_pd(), _CMP_GT_OQ));
        const __m128i pack = _mm_load_si128(reinterpret_cast<const __m128i*>(packTable.bytes[taking]));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(list + n), _mm_shuffle_epi8(ids, pack));
        n += __builtin_popcount((unsigned) taking);
        ids = _mm_add_epi32(ids, _mm_set1_epi32(4));
    }
#endif
#if SNARESIM_VECTOR_TARGETS && SNARESIM_VECTOR_BYTES == 64
    __m512i ids = _mm512_add_epi32(_mm512_set1_epi32(first), _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
    for (; i + 16 <= count; i += 16)
    {
        const unsigned low = _mm512_cmp_pd_mask(_mm512_loadu_pd(reach + i), _mm512_setzero_pd(), _CMP_GT_OQ);
        const unsigned high = _mm512_cmp_pd_mask(_mm512_loadu_pd(reach + i + 8), _mm512_setzero_pd(), _CMP_GT_OQ);
        const __mmask16 taking = (__mmask16) (low | high << 8);
        _mm512_storeu_si512(list + n, _mm512_maskz_compress_epi32(taking, ids));
        n += __builtin_popcount(taking);
        ids = _mm512_add_epi32(ids, _mm512_set1_epi32(16));
    }
#endif
    for (; i < count; ++i)
    {
        list[n] = first + i;
        n += reach[i] > 0.0 ? 1 : 0;
    }
    return n;
}

// Each class's groups whose reach is positive (listReaching), class by class, into list, and
// the classes they form into active (their sizes; their groups from 0 in list, their points
// from 0 member-major); returns how many classes, their groups in groups and points in points.
int listReachingClasses(const SnareContact::SizeClass* classes, int numClasses, const double* __restrict reach, int* __restrict list,
                        SnareContact::SizeClass* __restrict active, int& groups, int& points)
{
    int count = 0;
    groups = points = 0;
    for (int c = 0; c < numClasses; ++c)
    {
        const SnareContact::SizeClass& k = classes[c];
        const int n = listReaching(k.groupCount, reach + k.groupBegin, k.groupBegin, list + groups);
        if (n == 0)
            continue;
        active[count++] = { k.size, groups, n, points };
        groups += n;
        points += k.size * n;
    }
    return count;
}
// The points of active's classes (listReachingClasses: groups[g] the g-th group taking part),
// member-major by class, into points (their places in classes' layout), with each one's group
// (g) into pointGroup. One class per size, in the same order in both.
void listPoints(const SnareContact::SizeClass* classes, const SnareContact::SizeClass* active, int numActive, const int* __restrict groups,
                int* __restrict points, int* __restrict pointGroup)
{
    for (int a = 0, c = 0; a < numActive; ++a)
    {
        while (classes[c].size != active[a].size)
            ++c;
        const SnareContact::SizeClass &k = classes[c], &s = active[a];
        const int* in = groups + s.groupBegin;
        for (int j = 0, t = s.pointBegin; j < k.size; ++j, t += s.groupCount)
        {
            const int offset = k.pointBegin + j * k.groupCount - k.groupBegin;
            for (int i = 0; i < s.groupCount; ++i)
            {
                points[t + i] = offset + in[i];
                pointGroup[t + i] = s.groupBegin + i;
            }
        }
    }
}
// The solve's points gathered (index: their places among all points): their wire nodes, xi^{n-1},
// xi^n and psi.
void gatherSolvedPoints(int count, const int* __restrict index, const int* __restrict wireNode, const double* __restrict xiPrev,
                        const double* __restrict xiNow, const double* __restrict psi, int* __restrict outWireNode,
                        double* __restrict outXiPrev, double* __restrict outXiNow, double* __restrict outPsi)
{
#pragma omp simd
    for (int t = 0; t < count; ++t)
    {
        const int k = index[t];
        outWireNode[t] = wireNode[k];
        outXiPrev[t] = xiPrev[k];
        outXiNow[t] = xiNow[k];
        outPsi[t] = psi[k];
    }
}
// The solve's xi^{n+1} and psi put back in their places (index, distinct).
void scatterSolvedPoints(int count, const int* __restrict index, const double* __restrict xiNext, const double* __restrict psi,
                         double* __restrict toXiNext, double* __restrict toPsi)
{
#pragma omp simd
    for (int t = 0; t < count; ++t)
    {
        toXiNext[index[t]] = xiNext[t];
        toPsi[index[t]] = psi[t];
    }
}

// out[t] = from[index[t]] (a gather).
template <typename T>
void gatherPoints(int count, const int* __restrict index, const T* __restrict from, T* __restrict out)
{
#pragma omp simd
    for (int t = 0; t < count; ++t)
        out[t] = from[index[t]];
}
