// A bounded, seeded mutation fuzzer for the constraint-file parser (run under ASan/UBSan by
// `make test-asan`): every conformance fixture is mutated byte-wise and structurally many times,
// and each result is parsed, looked up and resolved on the fixtures' rest grid. Any outcome but
// success or a ConstraintError (a crash, a sanitizer report, another exception) fails.
// MESHIK_FUZZ_ITERATIONS sets the number of mutated texts (default 100000).
#include "constraints_fixtures.h"
#include "meshik/constraints/constraint_file.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <random>

namespace mc = meshik::constraints;
using namespace meshik::constraints::testing;

namespace {

// Fragments that make or break JSON structure and the format's rules.
const std::vector<std::string> kTokens = {
    "{", "}", "[", "]", ",", ":", "\"", "\\", "\\u", "\\ud800", "0", "-1", "1e308", "1e999", "-0.0", "99999999999999999999",
    "null", "true", "NaN", "\"near\"", "\"radius\"", "\"matrix\"", "\"rotate\"", "\"translate\"", "\"frames\"",
    "\"handles\"", "\"_note\"", "[0, 0, 0]", "{\"axis\": [0, 0, 1], \"degrees\": 90}", "\xc4\xa7", "\xff", " ", "\n"};

// One mutation of `text` by `random`.
std::string mutate(std::string text, const std::vector<std::string>& corpus, std::mt19937_64& random) {
  const auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : std::size_t(random() % n); };
  const std::size_t at = pick(text.size() + 1);
  switch (random() % 6) {
    case 0:  // flip a byte
      if (!text.empty()) text[pick(text.size())] ^= static_cast<char>(1u << (random() % 8));
      break;
    case 1:  // insert a token
      text.insert(at, kTokens[pick(kTokens.size())]);
      break;
    case 2:  // delete a range
      text.erase(at, pick(16) + 1);
      break;
    case 3: {  // duplicate a range
      const std::size_t length = pick(64) + 1;
      text.insert(pick(text.size() + 1), text.substr(at, length));
      break;
    }
    case 4: {  // splice in a piece of another fixture
      const std::string& other = corpus[pick(corpus.size())];
      const std::size_t from = pick(other.size() + 1);
      text.insert(at, other.substr(from, pick(200) + 1));
      break;
    }
    default:  // replace a digit by another number
      for (std::size_t i = at; i < text.size(); ++i)
        if (std::isdigit(static_cast<unsigned char>(text[i]))) {
          text.replace(i, 1, std::to_string(static_cast<long long>(random() % 200) - 100));
          break;
        }
  }
  return text;
}

TEST(ConstraintsFuzz, MutatedFixturesParseOrRaiseConstraintError) {
  std::vector<std::string> good, corpus;  // corpus: good and bad fixtures
  for (const char* folder : {"/good", "/bad"})
    for (const auto& entry : std::filesystem::directory_iterator(fixtures_dir() + folder)) {
      corpus.push_back(read_text(entry.path().string()));
      if (folder == std::string("/good")) good.push_back(corpus.back());
    }
  ASSERT_GT(corpus.size(), 40u);
  const std::vector<double> rest = rest_vertices();
  const char* setting = std::getenv("MESHIK_FUZZ_ITERATIONS");
  const long iterations = setting ? std::atol(setting) : 100000;
  std::mt19937_64 random(20261123);
  long accepted = 0, refused = 0;
  for (long i = 0; i < iterations; ++i) {
    // Mostly good files, lightly mutated, so that many texts get past the parser to the checks
    // and the resolution.
    std::string text = random() % 4 != 0 ? good[random() % good.size()] : corpus[random() % corpus.size()];
    const int rounds = 1 + static_cast<int>(random() % 3);
    for (int r = 0; r < rounds; ++r) text = mutate(std::move(text), corpus, random);
    try {
      const mc::ConstraintDocument document = mc::parse_constraints(text, "fuzz.json");
      mc::find_frame(document, document.frames.back().name);
      mc::resolve_constraints(document, rest.data(), static_cast<std::int64_t>(rest.size() / 3));
      ++accepted;
    } catch (const mc::ConstraintError& error) {
      ASSERT_EQ(std::string(error.what()).rfind("fuzz.json: ", 0), 0u) << error.what();
      ++refused;
    }
  }
  // Both outcomes must occur, or the mutations are too weak (or too strong) to test anything.
  EXPECT_GT(accepted, iterations / 100);
  EXPECT_GT(refused, iterations / 2);
  std::printf("fuzz: %ld mutated texts, %ld accepted, %ld refused\n", iterations, accepted, refused);
}

}  // namespace
