#include "ccbuild/common/document.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

namespace ccbuild {
namespace {
using testing::contains;
using testing::expect_input_error;

TEST(Document, JsonValuesKnowTheirLines) {
  const Document doc =
      parse_json("{\n  \"a\": 1,\n  \"b\": [\n    2.5,\n    \"x\"\n  ]\n}\n", "t.json");
  const Field root = Field::root(doc);
  MapReader map(root, {"a", "b"});
  EXPECT_EQ(map.required("a").line(), 2);
  const auto items = map.required("b").items();
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[0].line(), 4);
  EXPECT_DOUBLE_EQ(items[0].as_number(), 2.5);
  EXPECT_EQ(items[1].line(), 5);
  EXPECT_TRUE(items[1].is_string());
  EXPECT_EQ(items[1].path(), "b[1]");
}

TEST(Document, JsonSyntaxErrorNamesLine) {
  const InputError e =
      expect_input_error([] { parse_json("{\n \"a\": [1,\n 2,,\n]}\n", "bad.json"); });
  EXPECT_EQ(e.first().file, "bad.json");
  EXPECT_EQ(e.first().line, 3);
  EXPECT_TRUE(contains(e.what(), "invalid JSON"));
}

TEST(Document, YamlSyntaxErrorNamesLine) {
  const InputError e = expect_input_error([] { parse_yaml("a: 1\nb: [1, 2\nc: 3\n", "bad.yaml"); });
  EXPECT_EQ(e.first().file, "bad.yaml");
  EXPECT_GT(e.first().line, 1);
  EXPECT_TRUE(contains(e.what(), "invalid YAML"));
}

TEST(Document, DuplicateKeysAreRejectedInBothEncodings) {
  const InputError y = expect_input_error([] { parse_yaml("a: 1\nb: 2\na: 3\n", "d.yaml"); });
  EXPECT_EQ(y.first().line, 3);
  EXPECT_TRUE(contains(y.what(), "appears twice"));
  const InputError j = expect_input_error([] { parse_json("{\"a\": 1,\n\"a\": 2}", "d.json"); });
  EXPECT_EQ(j.first().line, 2);
  EXPECT_TRUE(contains(j.what(), "appears twice"));
}

TEST(Document, UnknownKeySuggestsTheNearOne) {
  const Document doc = parse_yaml("id: 1\nthicknes: 0.2\n", "w.yaml");
  MapReader map(Field::root(doc), {"id", "thickness"});
  const InputError e = expect_input_error([&] { map.reject_unknown(); });
  EXPECT_EQ(e.first().line, 2);
  EXPECT_EQ(e.first().field, "thicknes");
  EXPECT_TRUE(contains(e.what(), "did you mean 'thickness'"));
}

TEST(Document, NumbersMustBeFiniteAndUnquoted) {
  const Document doc = parse_yaml("a: .nan\nb: \"12\"\nc: 1e3\nd: abc\ne: -inf\n", "n.yaml");
  MapReader map(Field::root(doc), {"a", "b", "c", "d", "e"});
  EXPECT_TRUE(
      contains(expect_input_error([&] { map.required("a").as_number(); }).what(), "finite"));
  EXPECT_TRUE(
      contains(expect_input_error([&] { map.required("b").as_number(); }).what(), "string"));
  EXPECT_DOUBLE_EQ(map.required("c").as_number(), 1000.0);
  EXPECT_TRUE(contains(expect_input_error([&] { map.required("d").as_number(); }).what(), "'abc'"));
  EXPECT_TRUE(
      contains(expect_input_error([&] { map.required("e").as_number(); }).what(), "finite"));
}

TEST(Document, MissingRequiredKeyIsNamed) {
  const Document doc = parse_yaml("walls:\n  - {id: 1, start: 2}\n", "m.yaml");
  const auto walls = MapReader(Field::root(doc), {"walls"}).required("walls").items();
  MapReader wall(walls[0], {"id", "start", "end"});
  const InputError e = expect_input_error([&] { wall.required("end"); });
  EXPECT_EQ(e.first().field, "walls[0]");
  EXPECT_EQ(e.first().line, 2);
  EXPECT_TRUE(contains(e.what(), "missing required key 'end'"));
}

TEST(Document, MissingFileIsNamed) {
  const InputError e = expect_input_error([] { load_document("/nonexistent/plan.yaml"); });
  EXPECT_EQ(e.first().file, "/nonexistent/plan.yaml");
  EXPECT_TRUE(contains(e.what(), "cannot open"));
}

// Found by tests/fuzz/fuzz.py (seed 2, site-00136): yaml-cpp's LoadAll never returned on a
// stray ',' where a value should start (an empty document at the same place, for ever).
TEST(Document, AStrayFlowEntryIsAnErrorNotAnEndlessStream) {
  for (const std::string text :
       {",\n", ", and a\n", "# a comment\n, and a\nx: 1\n", "start: 2027-03-01 07:00\n, and a\n"}) {
    const InputError e = expect_input_error([&] { parse_yaml(text, "site.yaml"); });
    EXPECT_EQ(e.first().file, "site.yaml") << text;
    EXPECT_GE(e.first().line, 1) << text;
  }
  // Empty and null documents stay what they were; a second document with content is named
  // at its first value.
  EXPECT_EQ(parse_yaml("", "e.yaml").root.kind, DocNode::Kind::kNull);
  EXPECT_EQ(parse_yaml("# only a comment\n", "e.yaml").root.kind, DocNode::Kind::kNull);
  EXPECT_EQ(parse_yaml("a: 1\n---\n", "e.yaml").root.kind, DocNode::Kind::kMap);
  const InputError second =
      expect_input_error([] { parse_yaml("a: 1\n---\n# c\nb: 2\n", "two.yaml"); });
  EXPECT_EQ(second.first().line, 4);
}

// Found by tests/fuzz/fuzz.py (seed 1, building-00063): a byte that is no UTF-8 reached an
// unknown-key message, and `validate --json` could not print it (exit 3).
TEST(Document, YamlThatIsNotUtf8IsRefusedWithItsLine) {
  const std::string text = "units: m\nwalls:\n  - {id\xff: 1}\n";
  const InputError e = expect_input_error([&] { parse_yaml(text, "plan.yaml"); });
  EXPECT_EQ(e.first().line, 3);
  EXPECT_TRUE(contains(e.what(), "not UTF-8"));
  for (const std::string bad : {"\xc3", "\xed\xa0\x80", "\xc0\xaf", "\xf4\x90\x80\x80"})
    EXPECT_THROW(parse_yaml("name: " + bad + "\n", "n.yaml"), InputError) << bad.size();
  EXPECT_NO_THROW(parse_yaml("name: \"\xc3\xa9\xe2\x82\xac\xf0\x9d\x84\x9e\"\n", "n.yaml"));
}

}  // namespace
}  // namespace ccbuild
