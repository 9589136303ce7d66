// The persistence format of bakes (render/bake_file.hpp): round trips, every single-bit flip
// caught by the checksum, and random mutations of valid files (flips, overwritten, cut, inserted
// and appended bytes; also mutated payloads with a recomputed checksum, which reach the
// payload's parsers): every read returns an error or a valid value, never reads out of bounds
// (the sanitizer build of scripts/test runs these cases under ASan and UBSan). The cache's
// payload parser (render::deserialize) is fuzzed the same way.
#include <catch2/catch.hpp>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "sphbasis/render/bake_file.hpp"
#include "sphbasis/render/representation.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

namespace {

/// A payload of the shape of a shard's: a string, a count, doubles.
std::vector<std::uint8_t> sample_payload() {
    ByteWriter w;
    w.str(R"({"shard":{"index":1,"count":4}})");
    w.u64(3);
    w.f64s({0.25, -1.0, 1e300, 0.0, 5e-324, 7.0});
    w.u32(0xdeadbeef);
    return w.take();
}

struct Parsed {
    std::string text;
    std::uint64_t stride = 0;
    std::vector<double> values;
    std::uint32_t tail = 0;
};

Parsed parse(const BakeFileView& v) {
    ByteReader r(v.payload, v.payload_size, "test");
    Parsed p;
    p.text = r.str();
    p.stride = r.u64();
    p.values = r.f64s();
    p.tail = r.u32();
    r.finish();
    return p;
}

/// One random mutation: 1 to 4 edits of flipped bits, overwritten, deleted, inserted or
/// appended bytes, or a cut.
std::vector<std::uint8_t> mutate(std::vector<std::uint8_t> b, std::mt19937_64& rng) {
    for (int m = 0, n = 1 + int(rng() % 4); m < n; ++m) {
        const std::size_t at = b.empty() ? 0 : rng() % b.size();
        switch (rng() % 6) {
            case 0:
                if (!b.empty()) b[at] ^= std::uint8_t(1u << (rng() % 8));
                break;
            case 1:
                if (!b.empty()) b[at] = std::uint8_t(rng());
                break;
            case 2:
                if (!b.empty()) b.erase(b.begin() + std::ptrdiff_t(at));
                break;
            case 3:
                b.insert(b.begin() + std::ptrdiff_t(at), std::uint8_t(rng()));
                break;
            case 4:
                b.resize(b.size() + 1 + rng() % 16, std::uint8_t(rng()));
                break;
            default:
                b.resize(at);
        }
    }
    return b;
}

}  // namespace

TEST_CASE("bake file: round trip, header fields and errors", "[render][bake_file]") {
    const std::vector<std::uint8_t> payload = sample_payload();
    const std::vector<std::uint8_t> f =
        write_bake_file(BakeFileKind::shard, 0x0123456789abcdefull, payload);
    REQUIRE(f.size() == bake_file_header_bytes + payload.size());
    CHECK(std::string(f.begin(), f.begin() + 8) == "SPHBFILE");
    CHECK(f[8] == bake_file_version);
    CHECK(f[12] == 1);
    CHECK(f[16] == 0xef);  // little-endian
    const BakeFileView v = read_bake_file(f, BakeFileKind::shard);
    CHECK(v.input_hash == 0x0123456789abcdefull);
    CHECK(std::vector<std::uint8_t>(v.payload, v.payload + v.payload_size) == payload);
    const Parsed p = parse(v);
    CHECK(p.stride == 3);
    CHECK(p.values == std::vector<double>{0.25, -1.0, 1e300, 0.0, 5e-324, 7.0});
    CHECK(p.tail == 0xdeadbeef);

    CHECK_THROWS_WITH(read_bake_file(f, BakeFileKind::cache), Catch::Contains("kind"));
    std::vector<std::uint8_t> g = f;
    g[8] = 2;
    CHECK_THROWS_WITH(read_bake_file(g, BakeFileKind::shard), Catch::Contains("version"));
    g = f;
    g.pop_back();
    CHECK_THROWS_WITH(read_bake_file(g, BakeFileKind::shard), Catch::Contains("truncated"));
    g = f;
    g[0] = 'X';
    CHECK_THROWS_WITH(read_bake_file(g, BakeFileKind::shard), Catch::Contains("magic"));
    CHECK_THROWS_AS(read_bake_file(std::vector<std::uint8_t>{}, BakeFileKind::shard),
                    std::runtime_error);
    // An empty payload is a valid file.
    const std::vector<std::uint8_t> e = write_bake_file(BakeFileKind::cache, 7, {});
    CHECK(read_bake_file(e, BakeFileKind::cache).payload_size == 0);

    // The input hash: length-prefixed blocks, so a split point is part of the hash.
    CHECK(InputHash().str("ab").str("c").value() != InputHash().str("a").str("bc").value());
    CHECK(InputHash().str("ab").value() == InputHash().str("ab").value());
    CHECK(InputHash().f64(0.0).value() != InputHash().f64(-0.0).value());
}

TEST_CASE("bake file: every single-bit flip is refused", "[render][bake_file]") {
    const std::vector<std::uint8_t> f = write_bake_file(BakeFileKind::shard, 42, sample_payload());
    std::size_t refused = 0;
    for (std::size_t i = 0; i < f.size(); ++i)
        for (int bit = 0; bit < 8; ++bit) {
            std::vector<std::uint8_t> g = f;
            g[i] ^= std::uint8_t(1u << bit);
            try {
                (void)read_bake_file(g, BakeFileKind::shard);
            } catch (const std::runtime_error&) {
                ++refused;
            }
        }
    // Bits of the input hash are not checked by the container (the caller compares the hash),
    // but the checksum covers them.
    CHECK(refused == 8 * f.size());
}

TEST_CASE("bake file: random mutations give an error or a valid value", "[render][bake_file]") {
    const std::vector<std::uint8_t> payload = sample_payload();
    const std::vector<std::uint8_t> f = write_bake_file(BakeFileKind::shard, 42, payload);
    std::mt19937_64 rng(20261205);
    std::size_t refused = 0, parsed = 0;
    for (int it = 0; it < 3000; ++it) {
        // Half of the mutations hit the whole file; the other half hit the payload only and are
        // framed with a correct checksum, so that the payload reader meets them.
        const bool framed = it % 2 == 1;
        const std::vector<std::uint8_t> g =
            framed ? write_bake_file(BakeFileKind::shard, 42, mutate(payload, rng))
                   : mutate(f, rng);
        try {
            const Parsed p = parse(read_bake_file(g, BakeFileKind::shard));
            CHECK(p.values.size() * 8 < g.size());
            ++parsed;
        } catch (const std::runtime_error& e) {
            CHECK(std::string(e.what()).rfind("sphbasis::", 0) == 0);
            ++refused;
        }
    }
    CHECK(refused > 2000);
    CHECK(parsed + refused == 3000);
}

TEST_CASE("bake file: mutated cache entries give an error or a valid BakeData",
          "[render][bake_file]") {
    BakeData d;
    d.request.where = BakeRequest::Where::vertex;
    d.request.settings.quantities = Quantity::ao | Quantity::bent;
    d.results.resize(3);
    for (std::size_t i = 0; i < 3; ++i) {
        d.results[i].ao = 0.25 * double(i);
        d.results[i].bent = {0, 0, 1};
    }
    const std::vector<std::uint8_t> payload = serialize(d);
    std::mt19937_64 rng(7);
    std::size_t refused = 0;
    for (int it = 0; it < 2000; ++it) {
        const std::vector<std::uint8_t> g =
            it % 2 ? write_bake_file(BakeFileKind::cache, 9, mutate(payload, rng))
                   : mutate(write_bake_file(BakeFileKind::cache, 9, payload), rng);
        try {
            const BakeFileView v = read_bake_file(g, BakeFileKind::cache);
            const BakeData back =
                deserialize(std::vector<std::uint8_t>(v.payload, v.payload + v.payload_size));
            CHECK(back.results.size() <= g.size());
        } catch (const std::runtime_error&) {
            ++refused;
        }
    }
    CHECK(refused > 1000);
}
