// drape::Fnv1a: FNV-1a's steps from the project's offset basis (fnv1a.hpp),
// against values computed from that definition in Python:
//   h = 1469598103934665603
//   for c in b"foobar": h = ((h ^ c) * 1099511628211) % 2**64
#include <drape/fnv1a.hpp>

#include <catch2/catch.hpp>

TEST_CASE("Fnv1a hashes bytes by FNV-1a's steps from the project's offset basis", "[framework][hash]") {
  CHECK(drape::Fnv1a().text("").value() == 1469598103934665603ull);
  CHECK(drape::Fnv1a().text("a").value() == 0x44bd8ad473cd9906ull);
  CHECK(drape::Fnv1a().text("foobar").value() == 0x88fad7c0a8ff07f2ull);
  CHECK(drape::Fnv1a().text("foobar").hex() == "88fad7c0a8ff07f2");
  // From the published basis, FNV-1a's published test vector.
  CHECK(drape::Fnv1a(14695981039346656037ull).text("foobar").value() == 0x85944171f73967e8ull);
  // Bytes in pieces hash as the whole.
  CHECK(drape::Fnv1a().text("foo").text("bar").value() == drape::Fnv1a().text("foobar").value());
}
