#pragma once

/// @file
/// Small inline demonstration-log texts: one good log and one malformed variant per rule of the
/// reader, each with the parts its error message must contain (the line and the column).

#include <string>
#include <vector>

#include "learning_data/demo_log.hpp"

namespace graspsynth::testing {

/// The header row of format v1.
inline std::string DemoHeader() {
  std::string header;
  for (const std::string& name : DemoColumns()) header += (header.empty() ? "" : ",") + name;
  return header + "\n";
}

/// A sample row: time t, wrist at (x, 0.2, 0.3), quaternion (qw, qx, 0, 0), fingers 0.1,
/// `event` (text as written), object centre (-0.25, 0.85, object_z).
inline std::string DemoRow(const std::string& t, const std::string& event, double x = 0.1,
                           const std::string& qw = "1", const std::string& qx = "0",
                           const std::string& object_z = "0.025") {
  std::string row = t + "," + std::to_string(x) + ",0.2,0.3," + qw + "," + qx + ",0,0";
  for (int i = 0; i < kHandDof; ++i) row += ",0.1";
  return row + "," + event + ",-0.25,0.85," + object_z + "\n";
}

/// The metadata block of a good log (3 lines).
inline std::string DemoMetadataText() {
  return "# format: graspsynth-demo/1\n# theta_deg: 40\n# object_position: -0.25, 0.85, 0.025\n";
}

/// A good log: metadata (lines 1-3), header (line 4), samples on lines 5-8, grasp on line 7,
/// end on line 8.
inline std::string GoodDemoText() {
  return DemoMetadataText() + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0") +
         DemoRow("0.2", "1") + DemoRow("0.3", "2", 0.1, "1", "0", "0.2");
}

/// A malformed log and what its error message must contain.
struct MalformedCase {
  std::string name;                  ///< also the file name stem in directory tests
  std::string text;                  ///< the file's contents
  std::vector<std::string> message;  ///< substrings after the "<file>:" prefix
};

/// One case per rule of the reader.
inline std::vector<MalformedCase> MalformedDemoCases() {
  const std::string meta = DemoMetadataText();
  const std::string good_rows =
      DemoRow("0", "0") + DemoRow("0.1", "0") + DemoRow("0.2", "1") + DemoRow("0.3", "2");
  std::string missing_column = DemoHeader();
  missing_column.erase(missing_column.find("wrist_z,"), 8);
  std::string wrong_name = DemoHeader();
  wrong_name.replace(wrong_name.find("wrist_y"), 7, "wrist_Y");
  std::string short_row = DemoRow("0.1", "0");
  short_row.erase(short_row.rfind(','));
  short_row += "\n";
  std::string long_row = DemoRow("0.1", "0");
  long_row.insert(long_row.size() - 1, ",7");

  return {
      {"missing_column",
       meta + missing_column + good_rows,
       {":4:", "header column 4", "expected 'wrist_z'", "got 'wrist_qw'"}},
      {"wrong_column_name",
       meta + wrong_name + good_rows,
       {":4:", "header column 3", "expected 'wrist_y'", "got 'wrist_Y'"}},
      {"nan_value",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0", 0.1, "nan") +
           DemoRow("0.2", "1") + DemoRow("0.3", "2"),
       {":6:", "column 5 'wrist_qw'", "not a finite number", "'nan'"}},
      {"infinite_value",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("inf", "0") + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "column 1 't'", "'inf'"}},
      {"non_unit_quaternion",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0", 0.1, "1", "0.1") +
           DemoRow("0.2", "1") + DemoRow("0.3", "2"),
       {":6:", "columns 5-8 'wrist_qw'..'wrist_qz'", "norm 1.00498", "not 1"}},
      {"position_beyond_bound",  // finite, but its sums would overflow
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0", 1e300) + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "column 2 'wrist_x'", "is beyond +-100 m"}},
      {"time_beyond_bound",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0") + DemoRow("0.2", "1") +
           DemoRow("2e6", "2"),
       {":8:", "column 1 't'", "'2e6' is beyond +-1e+06 s"}},
      {"object_position_beyond_bound",
       "# format: graspsynth-demo/1\n# theta_deg: 40\n# object_position: -0.25, -1e200, 0\n" +
           DemoHeader() + good_rows,
       {":3:", "metadata 'object_position'", "component 2", "'-1e200'", "beyond +-100 m"}},
      {"time_going_back",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0") + DemoRow("0.05", "1") +
           DemoRow("0.3", "2"),
       {":7:", "column 1 't'", "time 0.05 s does not increase", "line 6 has t = 0.1"}},
      {"repeated_time",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0", "0") + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "column 1 't'", "does not increase"}},
      {"no_grasp_event",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0") + DemoRow("0.2", "0") +
           DemoRow("0.3", "2"),
       {":8:", "column 25 'event'", "no grasp event"}},
      {"two_grasp_events",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "1") + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":7:", "column 25 'event'", "second grasp event", "first is on line 6"}},
      {"bad_event_value",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "3") + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "column 25 'event'", "must be 0, 1 or 2", "'3'"}},
      {"no_end_event",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "0") + DemoRow("0.2", "1") +
           DemoRow("0.3", "0"),
       {":8:", "column 25 'event'", "not an end event", "truncated"}},
      {"sample_after_end",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "1") + DemoRow("0.2", "2") +
           DemoRow("0.3", "0"),
       {":8:", "after the end event on line 7"}},
      {"empty_file", "", {": empty file"}},
      {"blank_file", "  \n\n", {": empty file"}},
      {"header_only", meta + DemoHeader(), {":4:", "no samples after the header"}},
      {"metadata_only", meta, {"no header row"}},
      {"missing_theta",
       "# format: graspsynth-demo/1\n# object_position: -0.25,0.85,0.025\n" + DemoHeader() +
           good_rows,
       {":3:", "missing required metadata '# theta_deg: ...'"}},
      {"missing_format",
       "# theta_deg: 40\n# object_position: -0.25,0.85,0.025\n" + DemoHeader() + good_rows,
       {":3:", "missing required metadata '# format: ...'"}},
      {"missing_object_position",
       "# format: graspsynth-demo/1\n# theta_deg: 40\n" + DemoHeader() + good_rows,
       {":3:", "missing required metadata '# object_position: ...'"}},
      {"wrong_format_version",
       "# format: graspsynth-demo/2\n# theta_deg: 40\n# object_position: -0.25,0.85,0.025\n" +
           DemoHeader() + good_rows,
       {":1:", "metadata 'format'", "expected 'graspsynth-demo/1'", "got 'graspsynth-demo/2'"}},
      {"bad_theta",
       "# format: graspsynth-demo/1\n# theta_deg: forty\n# object_position: -0.25,0.85,0.025\n" +
           DemoHeader() + good_rows,
       {":2:", "metadata 'theta_deg'", "'forty'"}},
      {"short_object_position",
       "# format: graspsynth-demo/1\n# theta_deg: 40\n# object_position: -0.25,0.85\n" +
           DemoHeader() + good_rows,
       {":3:", "metadata 'object_position'", "found 2 fields"}},
      {"duplicate_metadata",
       meta + "# theta_deg: 50\n" + DemoHeader() + good_rows,
       {":4:", "metadata 'theta_deg' appears twice", "line 2"}},
      {"bad_metadata_line",
       meta + "# no colon here\n" + DemoHeader() + good_rows,
       {":4:", "expected a metadata line '# key: value'"}},
      {"too_few_fields",
       meta + DemoHeader() + DemoRow("0", "0") + short_row + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "expected 28 fields, found 27", "column 28 'object_z' is missing"}},
      {"too_many_fields",
       meta + DemoHeader() + DemoRow("0", "0") + long_row + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "expected 28 fields, found 29", "column 29"}},
      {"empty_field",
       meta + DemoHeader() + DemoRow("0", "0") + DemoRow("0.1", "") + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "column 25 'event'", "not a finite number: ''"}},
      {"blank_line_between_rows",
       meta + DemoHeader() + DemoRow("0", "0") + "\n" + DemoRow("0.1", "0") + DemoRow("0.2", "1") +
           DemoRow("0.3", "2"),
       {":6:", "blank line between sample rows"}},
      {"metadata_after_header",
       meta + DemoHeader() + DemoRow("0", "0") + "# trial: 3\n" + DemoRow("0.1", "1") +
           DemoRow("0.3", "2"),
       {":6:", "after the header"}},
  };
}

}  // namespace graspsynth::testing
