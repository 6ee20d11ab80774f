// The field lists the two decodings are built from (idl_field_lists.h) name every field of every
// struct of idl/gearpath.idl, in order: a field missing from a list would be compared by
// neither side, so the interoperability test would not notice it decoded wrongly.
#include "tests/interop/idl_field_lists.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace gearpath::testing {
namespace {

using FieldsByStruct = std::map<std::string, std::vector<std::string>>;

// struct name -> member names, from the IDL text: every `@final struct X { ... };`, one member
// declaration per statement, the name being the last identifier before an optional array bound.
FieldsByStruct IdlStructs(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  const std::string idl = std::regex_replace(text.str(), std::regex("//[^\n]*"), "");
  FieldsByStruct structs;
  const std::regex struct_re(R"(struct\s+(\w+)\s*\{([^}]*)\})");
  const std::regex member_re(R"((\w+)\s*(\[[^\]]*\])?\s*;)");
  for (auto s = std::sregex_iterator(idl.begin(), idl.end(), struct_re);
       s != std::sregex_iterator(); ++s) {
    const std::string body = (*s)[2];
    auto& fields = structs[(*s)[1]];
    for (auto m = std::sregex_iterator(body.begin(), body.end(), member_re);
         m != std::sregex_iterator(); ++m) {
      fields.push_back((*m)[1]);
    }
  }
  return structs;
}

FieldsByStruct ListedStructs() {
#define GEARPATH_FIELD_NAME(name) #name,
#define GEARPATH_STRUCT_ENTRY(Type) {#Type, {GEARPATH_FIELDS_##Type(GEARPATH_FIELD_NAME)}},
  return FieldsByStruct{GEARPATH_IDL_STRUCTS(GEARPATH_STRUCT_ENTRY)};
#undef GEARPATH_STRUCT_ENTRY
#undef GEARPATH_FIELD_NAME
}

TEST(IdlFieldLists, NameEveryFieldOfEveryIdlStructInOrder) {
  const FieldsByStruct idl = IdlStructs(GEARPATH_SOURCE_DIR "/idl/gearpath.idl");
  ASSERT_GE(idl.size(), 14u) << "the IDL parse found too few structs";
  EXPECT_EQ(ListedStructs(), idl);
}

}  // namespace
}  // namespace gearpath::testing
