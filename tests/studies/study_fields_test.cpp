// Tests of studies/study_fields.hpp: StudyRow's field list is the one description of the row. A
// field listed with a JSON pointer is in synthesis.json's rows, one with a column is in
// synthesis.csv's header (which is kStudySynthesisCsvHeader), and every field is in the bytes.

#include "studies/study_fields.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "common/field_codec.hpp"
#include "common/field_text.hpp"
#include "studies/study_codec.hpp"
#include "studies/study_report.hpp"
#include "tests/utils/study_rows.hpp"

namespace graspsynth {
namespace {

using nlohmann::json;
using testing::FullRow;

TEST(StudyFields, TheCsvHeaderIsTheListsColumns) {
  const std::string csv = StudySynthesisCsv({});
  EXPECT_EQ(csv, std::string(kStudySynthesisCsvHeader) + "\n");
  // a row at a position of its own adds x and y in front.
  EXPECT_EQ(StudySynthesisCsv({FullRow()}).substr(0, csv.size() + 4),
            "x,y," + std::string(kStudySynthesisCsvHeader) + "\n");
}

// Each field that names a JSON pointer is at that pointer in StudyRowsJson's row, and each that
// names a CSV column has that column's header.
struct Places {
  const json& row;
  const std::string& header;
  int json_fields = 0, csv_fields = 0;
  template <class T>
  void operator()(const Field& f, const T&) {
    if (f.json) {
      ++json_fields;
      EXPECT_TRUE(row.contains(json::json_pointer(f.json))) << f.name << " at " << f.json;
    }
    if (f.csv >= 0) {
      ++csv_fields;
      const std::string name = f.csv_header ? f.csv_header : f.name;
      EXPECT_NE(("," + header + ",").find("," + name + ","), std::string::npos) << f.name;
    }
  }
};

TEST(StudyFields, EveryListedFieldIsInTheJsonAndTheCsv) {
  const StudyRow row = FullRow();
  const json rows = json::parse(StudyRowsJson({row}))["rows"];
  const std::string csv = StudySynthesisCsv({row});
  const std::string header = csv.substr(0, csv.find('\n'));
  Places places{rows[0], header};
  VisitFields(places, row);
  EXPECT_EQ(places.json_fields, 29);
  EXPECT_EQ(places.csv_fields, 18);
  EXPECT_EQ(FieldCount<StudyRow>(), 32u);
  // the JSON has nothing the list does not put there.
  EXPECT_EQ(rows[0].size(), 20u);
}

// Sets the index-th field to its type's default.
struct Reset {
  size_t index, at = 0;
  bool& changed;
  template <class T>
  void operator()(const Field&, T& value) {
    if (at++ == index) {
      value = T{};
      changed = true;
    }
  }
};

TEST(StudyFields, EveryFieldIsInTheBytes) {
  // each field changed alone changes the bytes: a field left out of the list would not.
  const std::string full = EncodeStudyRow(FullRow());
  for (size_t k = 0; k < FieldCount<StudyRow>(); ++k) {
    StudyRow row = FullRow();
    bool changed = false;
    Reset reset{k, 0, changed};
    VisitFields(reset, row);
    ASSERT_TRUE(changed);
    EXPECT_NE(EncodeStudyRow(row), full) << "field " << k;
  }
}

}  // namespace
}  // namespace graspsynth
