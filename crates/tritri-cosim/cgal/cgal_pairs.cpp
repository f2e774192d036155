// The software baseline: CGAL's answer to "which triangles of A meet which
// of B", as CGAL's users write it: box_intersection_d over the triangles'
// bounding boxes (closed boxes), and do_intersect on the Epick kernel
// (exact predicates) for each pair whose boxes overlap. One thread.
//
// Compiled and run by tritri-cosim's `cgal` module (cgal.rs), which writes
// the triangles and reads the answer:
//
//   cgal_pairs TRIANGLES REPEATS PAIRS
//
// TRIANGLES: little-endian u64 count of A, u64 count of B, then each
// triangle's nine f64 coordinates, A's then B's. The query runs REPEATS
// times from the triangles in memory; each run's seconds go to stdout as
// `seconds S`, then `boxes N` (pairs whose boxes overlap) and `pairs N`;
// the pairs, `i j` one a line in increasing order, go to PAIRS.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <utility>
#include <vector>

typedef CGAL::Exact_predicates_inexact_constructions_kernel K;
typedef K::Triangle_3 Triangle;
typedef CGAL::Box_intersection_d::Box_with_handle_d<double, 3, const Triangle*> Box;

static std::vector<Triangle> read_triangles(std::ifstream& in, std::uint64_t n) {
    std::vector<Triangle> out;
    out.reserve(n);
    for (std::uint64_t t = 0; t < n; ++t) {
        double c[9];
        in.read(reinterpret_cast<char*>(c), sizeof c);
        out.emplace_back(K::Point_3(c[0], c[1], c[2]), K::Point_3(c[3], c[4], c[5]),
                         K::Point_3(c[6], c[7], c[8]));
    }
    return out;
}

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: cgal_pairs TRIANGLES REPEATS PAIRS\n");
        return 2;
    }
    std::ifstream in(argv[1], std::ios::binary);
    std::uint64_t na = 0, nb = 0;
    in.read(reinterpret_cast<char*>(&na), 8);
    in.read(reinterpret_cast<char*>(&nb), 8);
    std::vector<Triangle> a = read_triangles(in, na);
    std::vector<Triangle> b = read_triangles(in, nb);
    if (!in) {
        std::fprintf(stderr, "%s: shorter than its %llu + %llu triangles\n", argv[1],
                     (unsigned long long)na, (unsigned long long)nb);
        return 1;
    }
    const int repeats = std::atoi(argv[2]);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
    std::size_t boxes = 0;
    for (int r = 0; r < repeats; ++r) {
        pairs.clear();
        boxes = 0;
        auto started = std::chrono::steady_clock::now();
        std::vector<Box> boxes_a, boxes_b;
        boxes_a.reserve(a.size());
        boxes_b.reserve(b.size());
        for (const Triangle& t : a) boxes_a.emplace_back(t.bbox(), &t);
        for (const Triangle& t : b) boxes_b.emplace_back(t.bbox(), &t);
        CGAL::box_intersection_d(
            boxes_a.begin(), boxes_a.end(), boxes_b.begin(), boxes_b.end(),
            [&](const Box& x, const Box& y) {
                ++boxes;
                if (CGAL::do_intersect(*x.handle(), *y.handle())) {
                    pairs.emplace_back(std::uint32_t(x.handle() - a.data()),
                                       std::uint32_t(y.handle() - b.data()));
                }
            });
        std::chrono::duration<double> took = std::chrono::steady_clock::now() - started;
        std::printf("seconds %.9f\n", took.count());
    }
    std::sort(pairs.begin(), pairs.end());
    std::printf("boxes %zu\npairs %zu\n", boxes, pairs.size());
    std::FILE* out = std::fopen(argv[3], "w");
    if (!out) {
        std::perror(argv[3]);
        return 1;
    }
    for (const auto& p : pairs) std::fprintf(out, "%u %u\n", p.first, p.second);
    return std::fclose(out) == 0 ? 0 : 1;
}
