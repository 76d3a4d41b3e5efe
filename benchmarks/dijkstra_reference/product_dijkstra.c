/* A blind (no heuristic) exact Dijkstra over the product graph (traversable cells x automaton states).
 *
 * Written for the benchmarks as an independent reference, from the problem's raw inputs only (occupancy
 * raster, label raster, automaton table, stairs links, start), not from sgplan.planning's data:
 *   - nodes: (cell, q) for every traversable cell and automaton state q;
 *   - moves: the 8 grid neighbours on the same floor (Euclidean cost with the per-axis resolution) and the
 *     stairs links in both directions (their own cost); entering a cell reads its label: q' = T(q, label);
 *   - the search stops at the first popped state whose q is accepting (its g is the optimum).
 * States from which the automaton can no longer accept ("dead") are never pushed: that only removes
 * useless work and keeps the reference as fast as a plain blind search can be.
 *
 * Costs are doubles, the heap is a binary heap of (g, state) with lazy deletion; per-state memory is
 * calloc'ed (committed page by page as the search touches it).
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct {
    double key;
    int64_t state;
} Entry;

static double now_s(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int heap_push(Entry **heap, int64_t *size, int64_t *cap, double key, int64_t state) {
    if (*size >= *cap) {
        int64_t ncap = *cap * 2;
        Entry *grown = (Entry *)realloc(*heap, (size_t)ncap * sizeof(Entry));
        if (!grown) return -1;
        *heap = grown;
        *cap = ncap;
    }
    Entry *h = *heap;
    int64_t i = (*size)++;
    while (i > 0) {
        int64_t parent = (i - 1) >> 1;
        if (h[parent].key <= key) break;
        h[i] = h[parent];
        i = parent;
    }
    h[i].key = key;
    h[i].state = state;
    return 0;
}

static Entry heap_pop(Entry *h, int64_t *size) {
    Entry top = h[0];
    Entry last = h[--(*size)];
    int64_t n = *size, i = 0;
    while (1) {
        int64_t child = 2 * i + 1;
        if (child >= n) break;
        if (child + 1 < n && h[child + 1].key < h[child].key) child++;
        if (h[child].key >= last.key) break;
        h[i] = h[child];
        i = child;
    }
    if (n > 0) h[i] = last;
    return top;
}

typedef struct {
    double *g;
    uint8_t *mark; /* 0 new, 1 open, 2 closed */
    const int32_t *table;
    const int64_t *label;
    const uint8_t *alive;
    int64_t num_labels, num_q, size, cap, pushes, touched;
    Entry *heap;
} Search;

/* Offer (cell v, T(q, label(v))) at cost ng; returns -1 when out of memory. */
static inline int relax(Search *R, int32_t q, double ng, int64_t v) {
    int32_t nq = R->table[(int64_t)q * R->num_labels + R->label[v]];
    if (!R->alive[nq]) return 0;
    int64_t ns = v * R->num_q + nq;
    uint8_t mk = R->mark[ns];
    if (mk == 2 || (mk == 1 && ng >= R->g[ns])) return 0;
    if (mk == 0) R->touched++;
    R->g[ns] = ng;
    R->mark[ns] = 1;
    R->pushes++;
    return heap_push(&R->heap, &R->size, &R->cap, ng, ns);
}

/* Returns 0 on success (goal found or proved absent), -1 when out of memory.
 * stairs: (num_stairs, 6) int32 rows [floor_a, row_a, col_a, floor_b, row_b, col_b], each link usable
 * both ways at stairs_cost. out: [cost (inf without a path), search seconds, setup seconds, pops,
 * pushes, states touched, goal cell raster index, goal q]. */
int product_dijkstra(int32_t floors, int32_t rows, int32_t cols, const uint8_t *traversable,
                     const int64_t *labels, int32_t num_q, int64_t num_labels, const int32_t *table,
                     const uint8_t *accepting, int32_t num_stairs, const int32_t *stairs,
                     const double *stairs_cost, double res_x, double res_y, int32_t start_floor,
                     int32_t start_row, int32_t start_col, int32_t q_start, double *out) {
    double t0 = now_s();
    const int64_t plane = (int64_t)rows * cols, raster = plane * floors;
    int64_t n = 0;
    int32_t *index = (int32_t *)malloc((size_t)raster * sizeof(int32_t));
    if (!index) return -1;
    for (int64_t i = 0; i < raster; i++) index[i] = traversable[i] ? (int32_t)n++ : -1;
    int64_t *where = (int64_t *)malloc((size_t)(n ? n : 1) * sizeof(int64_t));
    int64_t *label = (int64_t *)malloc((size_t)(n ? n : 1) * sizeof(int64_t));
    int32_t *stairs_ptr = (int32_t *)calloc((size_t)n + 1, sizeof(int32_t));
    int32_t *stairs_to = (int32_t *)malloc((size_t)(2 * num_stairs + 1) * sizeof(int32_t));
    double *stairs_w = (double *)malloc((size_t)(2 * num_stairs + 1) * sizeof(double));
    uint8_t *alive = (uint8_t *)malloc((size_t)num_q);
    if (!where || !label || !stairs_ptr || !stairs_to || !stairs_w || !alive) return -1;
    for (int64_t i = 0; i < raster; i++)
        if (index[i] >= 0) {
            where[index[i]] = i;
            label[index[i]] = labels[i];
        }
    /* stairs adjacency (CSR over cells), both directions */
    int32_t *ends = (int32_t *)malloc((size_t)(4 * num_stairs + 1) * sizeof(int32_t));
    int64_t m = 0;
    for (int32_t j = 0; j < num_stairs; j++) {
        const int32_t *s = stairs + 6 * j;
        int32_t a = index[((int64_t)s[0] * rows + s[1]) * cols + s[2]];
        int32_t b = index[((int64_t)s[3] * rows + s[4]) * cols + s[5]];
        if (a < 0 || b < 0) continue;
        ends[2 * m] = a; ends[2 * m + 1] = b; m++;
        ends[2 * m] = b; ends[2 * m + 1] = a; m++;
        stairs_w[m - 2] = stairs_w[m - 1] = stairs_cost[j];
    }
    double *w_tmp = (double *)malloc((size_t)(m + 1) * sizeof(double));
    memcpy(w_tmp, stairs_w, (size_t)m * sizeof(double));
    for (int64_t e = 0; e < m; e++) stairs_ptr[ends[2 * e] + 1]++;
    for (int64_t c = 0; c < n; c++) stairs_ptr[c + 1] += stairs_ptr[c];
    int32_t *fill = (int32_t *)calloc((size_t)n + 1, sizeof(int32_t));
    for (int64_t e = 0; e < m; e++) {
        int32_t a = ends[2 * e];
        int32_t slot = stairs_ptr[a] + fill[a]++;
        stairs_to[slot] = ends[2 * e + 1];
        stairs_w[slot] = w_tmp[e];
    }
    free(fill); free(w_tmp); free(ends);
    /* live automaton states: those from which some label sequence reaches acceptance */
    for (int32_t q = 0; q < num_q; q++) alive[q] = accepting[q] ? 1 : 0;
    for (int changed = 1; changed;) {
        changed = 0;
        for (int32_t q = 0; q < num_q; q++) {
            if (alive[q]) continue;
            for (int64_t l = 0; l < num_labels; l++)
                if (alive[table[(int64_t)q * num_labels + l]]) { alive[q] = 1; changed = 1; break; }
        }
    }
    const int dr[8] = {-1, -1, -1, 0, 0, 1, 1, 1}, dc[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
    double step[8];
    for (int k = 0; k < 8; k++) step[k] = sqrt((dr[k] * res_x) * (dr[k] * res_x) + (dc[k] * res_y) * (dc[k] * res_y));

    int64_t states = n * (int64_t)num_q;
    double *g = (double *)calloc((size_t)(states ? states : 1), sizeof(double));
    uint8_t *mark = (uint8_t *)calloc((size_t)(states ? states : 1), 1); /* 0 new, 1 open, 2 closed */
    int64_t cap = 1 << 16, size = 0;
    Entry *heap = (Entry *)malloc((size_t)cap * sizeof(Entry));
    if (!g || !mark || !heap) return -1;
    double t1 = now_s();

    double best = INFINITY;
    int64_t pops = 0, pushes = 0, touched = 0, goal = -1;
    int64_t start_cell = index[((int64_t)start_floor * rows + start_row) * cols + start_col];
    if (start_cell >= 0 && alive[q_start]) {
        int64_t s0 = start_cell * num_q + q_start;
        g[s0] = 0.0; mark[s0] = 1; touched = 1;
        heap_push(&heap, &size, &cap, 0.0, s0); pushes = 1;
    }
    Search R = {g, mark, table, label, alive, num_labels, num_q, size, cap, pushes, touched, heap};
    while (R.size > 0) {
        Entry e = heap_pop(R.heap, &R.size);
        int64_t s = e.state;
        if (mark[s] == 2 || e.key > g[s]) continue;
        mark[s] = 2;
        pops++;
        int64_t c = s / num_q;
        int32_t q = (int32_t)(s % num_q);
        if (accepting[q]) { best = e.key; goal = s; break; }
        int64_t pos = where[c];
        int64_t f = pos / plane, rc = pos % plane, r = rc / cols, col = rc % cols;
        for (int k = 0; k < 8; k++) {
            int64_t r2 = r + dr[k], c2 = col + dc[k];
            if (r2 < 0 || r2 >= rows || c2 < 0 || c2 >= cols) continue;
            int64_t v = index[f * plane + r2 * cols + c2];
            if (v >= 0 && relax(&R, q, e.key + step[k], v)) return -1;
        }
        for (int32_t j = stairs_ptr[c]; j < stairs_ptr[c + 1]; j++)
            if (relax(&R, q, e.key + stairs_w[j], stairs_to[j])) return -1;
    }
    pushes = R.pushes;
    touched = R.touched;
    heap = R.heap;
    double t2 = now_s();
    out[0] = best;
    out[1] = t2 - t1;
    out[2] = t1 - t0;
    out[3] = (double)pops;
    out[4] = (double)pushes;
    out[5] = (double)touched;
    out[6] = goal >= 0 ? (double)where[goal / num_q] : -1.0;
    out[7] = goal >= 0 ? (double)(goal % num_q) : -1.0;
    free(heap); free(mark); free(g); free(alive); free(stairs_w); free(stairs_to); free(stairs_ptr);
    free(label); free(where); free(index);
    return 0;
}
