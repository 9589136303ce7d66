// Tests of render/bake_record.hpp: the one packing of bake results, into `sphbasis bake`'s
// records (record_format 4) and into the representations' fields.
#include <catch2/catch.hpp>
#include <sphbasis/render/bake_record.hpp>
#include <sphbasis/render/representations/field.hpp>
#include <vector>

using namespace sphbasis;
using render::Quantity;

namespace {

// A result with every quantity, each number distinct: value v of list L is 100 L + v.
render::PointResult distinct_result(std::size_t b2, std::size_t nc) {
    render::PointResult r;
    r.ao = 0.25;
    r.ao_stderr = 0.5;
    r.bent = {0.1, 0.2, 0.3};
    r.bent_stderr = 0.4;
    auto list = [](int l, std::size_t n) {
        std::vector<double> v(n);
        for (std::size_t i = 0; i < n; ++i) v[i] = 100.0 * l + double(i);
        return v;
    };
    r.visibility = list(1, b2);
    r.visibility_stderr = list(2, b2);
    r.transfer = {list(3, b2), list(4, b2), list(5, b2)};
    r.transfer_stderr = list(6, b2);
    r.transfer_rgb = true;
    r.irradiance = {list(7, nc), list(8, nc), list(9, nc)};
    r.irradiance_stderr = list(10, nc);
    r.radiance = {list(11, b2), list(12, b2), list(13, b2)};
    r.radiance_stderr = list(14, b2);
    r.inside = true;
    r.transfer_matrix = {list(15, 9 * b2), list(16, 9 * b2), list(17, 9 * b2)};
    r.transfer_matrix_stderr = list(18, 9 * b2);
    return r;
}

}  // namespace

TEST_CASE("bake record: the layout of record_format 4", "[render][bake]") {
    // Offsets written out by hand for 3 bands (9 coefficients) and 9 irradiance coefficients:
    // ao 2, bent 4, visibility 2x9, transfer 4x9 + 1, irradiance 4x9, radiance 4x9 + 1, then the
    // high-to-low normal and hit (4).
    render::BakeSettings s;
    s.bands = 3;
    s.coeffs = 9;
    const render::RecordLayout L(s);
    CHECK(L.ao == 0);
    CHECK(L.bent == 2);
    CHECK(L.bent_se == 5);
    CHECK(L.vis == 6);
    CHECK(L.vis_se == 15);
    CHECK(L.tr == 24);
    CHECK(L.tr_se == 51);
    CHECK(L.tr_rgb == 60);
    CHECK(L.irr == 61);
    CHECK(L.irr_se == 88);
    CHECK(L.rad == 97);
    CHECK(L.rad_se == 124);
    CHECK(L.inside == 133);
    CHECK(L.h2l == 134);
    CHECK(L.stride == 138);
    // The blocks tile the record (with the 4 high-to-low numbers).
    std::size_t sum = 0;
    for (Quantity q : {Quantity::ao, Quantity::bent, Quantity::visibility, Quantity::transfer,
                       Quantity::irradiance, Quantity::radiance})
        sum += render::quantity_block_size(q, L.b2, L.nc);
    CHECK(sum + 4 == L.stride);
}

TEST_CASE("bake record: every number in its place, short lists padded, equal channels shared",
          "[render][bake]") {
    render::BakeSettings s;
    s.bands = 2;
    s.coeffs = 6;
    const render::RecordLayout L(s);
    const std::size_t b2 = 4, nc = 6;
    render::PointResult r = distinct_result(b2, nc);
    std::vector<double> rec = render::pack_records(L, {r});
    REQUIRE(rec.size() == L.stride);
    CHECK(rec[L.ao] == 0.25);
    CHECK(rec[L.ao + 1] == 0.5);
    CHECK(rec[L.bent + 1] == 0.2);
    CHECK(rec[L.bent_se] == 0.4);
    CHECK(rec[L.vis + 3] == 103);
    CHECK(rec[L.vis_se + 2] == 202);
    CHECK(rec[L.tr + 2 * b2 + 1] == 501);
    CHECK(rec[L.tr_se + 3] == 603);
    CHECK(rec[L.tr_rgb] == 1);
    CHECK(rec[L.irr + nc + 5] == 805);
    CHECK(rec[L.irr_se] == 1000);
    CHECK(rec[L.rad + 2 * b2] == 1300);
    CHECK(rec[L.rad_se + 1] == 1401);
    CHECK(rec[L.inside] == 1);

    // One transfer list (equal channels) stands for all three; a short list is padded with 0;
    // a quantity not baked is a block of zeros.
    r.transfer[0] = {1, 2};
    r.transfer[1].clear();
    r.transfer[2].clear();
    r.transfer_rgb = false;
    r.radiance = {};
    r.radiance_stderr = {};
    r.inside = false;
    rec = render::pack_records(L, {r});
    for (std::size_t c = 0; c < 3; ++c) {
        CHECK(rec[L.tr + c * b2] == 1);
        CHECK(rec[L.tr + c * b2 + 1] == 2);
        CHECK(rec[L.tr + c * b2 + 2] == 0);
        CHECK(rec[L.tr + c * b2 + 3] == 0);
    }
    CHECK(rec[L.tr_rgb] == 0);
    for (std::size_t i = L.rad; i < L.stride; ++i) CHECK(rec[i] == 0);
}

TEST_CASE("bake record: a field's channels are the record's values at float precision",
          "[render][bake]") {
    const std::size_t b2 = 9, nc = 4;
    const render::PointResult r = distinct_result(b2, nc);
    render::BakeSettings s;
    s.bands = 3;
    s.coeffs = int(nc);
    const render::RecordLayout L(s);
    const std::vector<double> rec = render::pack_records(L, {r});
    struct Case {
        Quantity q;
        std::size_t offset, channels;  // in the record
    };
    for (const Case& c :
         {Case{Quantity::ao | Quantity::bent, 0, 4}, Case{Quantity::visibility, L.vis, b2},
          Case{Quantity::ao | Quantity::transfer, L.tr, 3 * b2},
          Case{Quantity::irradiance, L.irr, 3 * nc}}) {
        s.quantities = c.q;
        REQUIRE(render::representations::channels_of(s) == int(c.channels));
        std::vector<float> f(c.channels);
        render::representations::pack(s, r, f.data());
        if (c.offset == 0) {  // ao, bent x, y, z
            CHECK(f[0] == float(rec[L.ao]));
            for (std::size_t i = 0; i < 3; ++i) CHECK(f[1 + i] == float(rec[L.bent + i]));
        } else {
            for (std::size_t i = 0; i < c.channels; ++i) CHECK(f[i] == float(rec[c.offset + i]));
        }
    }
    // The transfer matrix (not in the record): its block's values.
    s.quantities = Quantity::transfer_matrix;
    std::vector<float> f(std::size_t(render::representations::channels_of(s)));
    REQUIRE(f.size() == 27 * b2);
    render::representations::pack(s, r, f.data());
    CHECK(f[0] == 1500);
    CHECK(f[9 * b2 + 1] == 1601);
    CHECK(f[27 * b2 - 1] == float(1700 + 9 * b2 - 1));
}
