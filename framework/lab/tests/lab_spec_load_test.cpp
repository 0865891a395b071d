// Tests of the first step of the lab.json parser (framework/lab/src/lab_spec_load.cpp and
// parseLabSpec): syntax errors naming a line and a column, duplicate keys, and the limits on size,
// nesting and strings holding without a crash; and reading lab.json from disk (a missing file or
// folder, a folder where the file belongs, the origin of every message).
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "lab_spec_fixture.h"
#include "shaderlab/lab/lab_spec.h"

namespace {

using namespace lab_spec_test;

// =============================================================================================
// JSON syntax and the limits of the loader

using LabSpecSyntax = LabSpecFixture;

TEST_F(LabSpecSyntax, ParseErrorNamesLineAndColumn) {
    const LabSpecResult r = parseText("{\n  \"schema\": 2,\n  \"id\": \"01-phong\",\n  \"passes\": [,]\n}\n");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 4, column 14: syntax error", 0), 0u)
        << r.errors[0];
    EXPECT_NE(r.errors[0].find("unexpected ','"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, ColumnsCountCharactersNotBytes) {
    // "Ü" is two bytes in UTF-8, "€" three and "😀" four; the stray x is the 16th character.
    for (const std::string& text : {std::string("x"), std::string("\xC3\x9C"), std::string("\xE2\x82\xAC"),
                                    std::string("\xF0\x9F\x98\x80")}) {
        const LabSpecResult r = parseText("{\"title\": \"" + text + "\", x}");
        ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
        EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 1, column 16: ", 0), 0u) << r.errors[0];
    }
    const LabSpecResult r = parseText("{\"title\": \"\xC3\x9C\xC3\x9C\xC3\x9C\",\n \"\xE2\x82\xAC\": x}");
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 2, column 7: ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, TrailingCommaIsASyntaxError) {
    json spec = json::parse(kMinimalSpec);
    std::string text = spec.dump(2);
    text.insert(text.rfind('\n'), ",");  // after the last member: {..., "schema": 2,}
    const LabSpecResult r = parseText(text);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find("syntax error"), std::string::npos) << r.errors[0];
    EXPECT_NE(r.errors[0].find("unexpected '}'"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, TruncatedFileNamesTheEnd) {
    const LabSpecResult r = parseText("{\n  \"schema\": 2,\n");
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 3, column 1: ", 0), 0u) << r.errors[0];
    EXPECT_NE(r.errors[0].find("unexpected end of input"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, EmptyTextIsASyntaxError) {
    const LabSpecResult r = parseText("");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 1, column 1: ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, CommentsAreNotJson) {
    const LabSpecResult r = parseText("{\n  // a comment\n  \"schema\": 2\n}");
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0].rfind(std::string(kOrigin) + ": line 2, column ", 0), 0u) << r.errors[0];
}

TEST_F(LabSpecSyntax, NumberOverflowNamesItsLine) {
    json spec = json::parse(kBaseSpec);
    spec["scenes"][0]["time"] = 0.5;
    std::string text = spec.dump(2);
    const std::string needle = "\"time\": 0.5";
    ASSERT_NE(text.find(needle), std::string::npos);
    text.replace(text.find(needle), needle.size(), "\"time\": 1e999");
    std::size_t line = 1;
    for (std::size_t i = 0; i < text.find("1e999"); ++i) line += text[i] == '\n';
    const LabSpecResult r = parseText(text);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find(": line " + std::to_string(line) + ", column "), std::string::npos)
        << r.errors[0];
    EXPECT_NE(r.errors[0].find("1e999"), std::string::npos) << r.errors[0];
}

TEST_F(LabSpecSyntax, DuplicateKeysAreErrorsNamingTheirPath) {
    // A JSON reader keeps only the last of a repeated key; the first would silently vanish.
    const LabSpecResult r = parseText(R"({
      "schema": 2, "id": "01-phong",
      "passes": [{"name": "shade", "program": {"vertex": "phong.vert", "fragment": "phong.frag"},
                  "uniforms": {"u_a": 1, "u_a": 2}, "state": {"cull": "none"}, "state": {"cull": "back"}}],
      "scenes": [{"name": "sphere", "file": "scenes/sphere.gltf"},
                 {"name": "s2", "name": "s3", "file": "scenes/cube.glb"}],
      "targets": {"a b": {}, "a b": {}}
    })");
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[0].uniforms.u_a", "duplicate key"));
    EXPECT_TRUE(hasError(r, "passes[0].state", "duplicate key"));
    EXPECT_TRUE(hasError(r, "scenes[1].name", "duplicate key"));
    EXPECT_TRUE(hasError(r, "targets[\"a b\"]", "duplicate key"));
    EXPECT_EQ(r.errors.size(), 4u) << allErrors(r);
}

TEST_F(LabSpecSyntax, NestingIsLimitedTo32Levels) {
    // The root object, passes, the pass and its uniforms are four levels; then k arrays.
    auto nested = [](int k) {
        json spec = json::parse(kMinimalSpec);
        std::string value = std::string(static_cast<std::size_t>(k), '[') + "1" +
                            std::string(static_cast<std::size_t>(k), ']');
        std::string text = spec.dump();
        const std::string needle = "\"name\":\"shade\"";
        text.insert(text.find(needle), "\"uniforms\":{\"u_deep\":" + value + "},");
        return text;
    };
    const LabSpecResult at_limit = parseText(nested(28));
    EXPECT_TRUE(at_limit.ok) << allErrors(at_limit);
    const LabSpecResult deeper = parseText(nested(29));
    EXPECT_FALSE(deeper.ok);
    ASSERT_EQ(deeper.errors.size(), 1u) << allErrors(deeper);
    EXPECT_NE(deeper.errors[0].find("nested deeper than 32 levels"), std::string::npos) << deeper.errors[0];
    EXPECT_NE(deeper.errors[0].find("passes[0].uniforms.u_deep"), std::string::npos) << deeper.errors[0];

    // Far deeper than any stack would survive, unclosed or closed: refused, not a crash.
    const LabSpecResult abyss = parseText(std::string(500000, '['));
    ASSERT_EQ(abyss.errors.size(), 1u) << allErrors(abyss);
    EXPECT_NE(abyss.errors[0].find("nested deeper than 32 levels"), std::string::npos) << abyss.errors[0];
    const LabSpecResult closed = parseText(std::string(200000, '[') + std::string(200000, ']'));
    ASSERT_EQ(closed.errors.size(), 1u) << allErrors(closed);
    EXPECT_NE(closed.errors[0].find("nested deeper than 32 levels"), std::string::npos) << closed.errors[0];
}

TEST_F(LabSpecSyntax, StringsAreLimitedTo4096Bytes) {
    json spec = json::parse(kMinimalSpec);
    spec["$schema"] = std::string(4096, 'a');
    const LabSpecResult at_limit = parseJson(spec);
    EXPECT_TRUE(at_limit.ok) << allErrors(at_limit);

    spec["$schema"] = std::string(4097, 'a');
    const LabSpecResult longer = parseJson(spec);
    EXPECT_FALSE(longer.ok);
    EXPECT_TRUE(hasError(longer, "[\"$schema\"]", "a string of 4097 bytes is longer than the limit of 4096"));
    EXPECT_EQ(longer.errors.size(), 1u) << allErrors(longer);

    spec = json::parse(kMinimalSpec);
    spec["passes"][0]["uniforms"][std::string(100000, 'u')] = 1;  // a key: refused, not a crash
    const LabSpecResult long_key = parseJson(spec);
    EXPECT_FALSE(long_key.ok);
    EXPECT_TRUE(hasError(long_key, "passes[0].uniforms", "a key of 100000 bytes is too long"));
    EXPECT_EQ(long_key.errors.size(), 1u) << allErrors(long_key);
}

// =============================================================================================
// Reading lab.json from disk

using LabSpecFile = LabSpecFixture;

TEST_F(LabSpecFile, MissingLabJsonNamesThePath) {
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0], (lab_ / "lab.json").string() + ": file not found");
}

TEST_F(LabSpecFile, LabJsonThatIsAFolderIsRefused) {
    fs::create_directories(lab_ / "lab.json");
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0], (lab_ / "lab.json").string() + ": not a regular file");
}

TEST_F(LabSpecFile, MissingLabFolderNamesIt) {
    const std::string missing = (labs_ / "42-nothing").string();
    const LabSpecResult r = shaderlab::parseLabSpec(missing);
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_NE(r.errors[0].find("the lab folder " + missing + " does not exist"), std::string::npos)
        << r.errors[0];
}

TEST_F(LabSpecFile, FileOverOneMebibyteIsRefused) {
    std::string text = kMinimalSpec;
    text.insert(text.size() - 1, std::string((1u << 20) + 1 - text.size(), ' '));  // still valid JSON
    ASSERT_EQ(text.size(), (1u << 20) + 1);
    writeFile(lab_ / "lab.json", text);
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 1u) << allErrors(r);
    EXPECT_EQ(r.errors[0],
              (lab_ / "lab.json").string() + ": file is 1048577 bytes, more than the limit of 1048576");

    const LabSpecResult from_text = parseText(text);  // the text entry point has the same cap
    EXPECT_FALSE(from_text.ok);
    EXPECT_TRUE(hasError(from_text, "", "is 1048577 bytes, more than the limit of 1048576 (1 MiB)"));

    text.erase(text.size() - 2, 1);  // exactly 1 MiB: accepted
    ASSERT_EQ(text.size(), 1u << 20);
    writeFile(lab_ / "lab.json", text);
    const LabSpecResult at_limit = shaderlab::parseLabSpec(lab_.string());
    EXPECT_TRUE(at_limit.ok) << allErrors(at_limit);
}

TEST_F(LabSpecFile, ErrorsNameTheFileTheyCameFrom) {
    writeFile(lab_ / "lab.json", R"({"schema": 2, "id": "01-phong", "passes": []})");
    const LabSpecResult r = shaderlab::parseLabSpec(lab_.string());
    EXPECT_FALSE(r.ok);
    ASSERT_EQ(r.errors.size(), 2u) << allErrors(r);  // passes is empty; scenes is missing
    const std::string origin = (lab_ / "lab.json").string();
    for (const std::string& e : r.errors) EXPECT_EQ(e.rfind(origin + ": ", 0), 0u) << e;
}

}  // namespace
