// The one list of the server's parameters (param_specs.h) against what is written beside it:
// cfg/AmhaPlanner.cfg (names, types, ranges, defaults), config/planner.yaml (the defaults) and
// docs/ros.md (a row for each); and the checks that start-up and dynamic_reconfigure share.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include <dynamic_reconfigure/Config.h>

#include "amha_planner/lattice/lattice_planner.h"
#include "amha_planner/ros/param_specs.h"
#include "amha_planner/ros/reconfigure.h"

namespace amha_planner {
namespace {

using Type = ParamSpec::Type;

const ParamSpec* specNamed(const std::string& name) {
  for (const ParamSpec& s : paramSpecs())
    if (s.name == name) return &s;
  return nullptr;
}

// The value of `name` in a configuration message; false if it has none.
bool valueIn(const dynamic_reconfigure::Config& msg, const std::string& name, ParamValue* out) {
  for (const auto& e : msg.bools) {
    if (e.name == name) *out = e.value != 0;
  }
  for (const auto& e : msg.ints) {
    if (e.name == name) *out = static_cast<int>(e.value);
  }
  for (const auto& e : msg.doubles) {
    if (e.name == name) *out = e.value;
  }
  for (const auto& e : msg.strs) {
    if (e.name == name) *out = e.value;
  }
  const auto named = [&](const auto& entries) {
    for (const auto& e : entries)
      if (e.name == name) return true;
    return false;
  };
  return named(msg.bools) || named(msg.ints) || named(msg.doubles) || named(msg.strs);
}

dynamic_reconfigure::Config message(const AmhaPlannerConfig& c) {
  dynamic_reconfigure::Config msg;
  c.__toMessage__(msg);
  return msg;
}

// The default the .cfg and the .yaml state: PlannerParams{}'s, except for the A-MHA* weights,
// which PlannerParams leaves at -1 (the algorithm's preset) and the files spell out.
ParamValue statedDefault(const ParamSpec& s) {
  const amha::PlannerConfig amha = amha::lattice::defaultPlannerConfig(amha::Algorithm::kAmhaStar);
  const std::map<std::string, double> presets = {
      {"w1", amha.w1}, {"w2", amha.w2}, {"dw1", amha.dw1}, {"dw2", amha.dw2}};
  const auto it = presets.find(s.name);
  return it != presets.end() ? ParamValue(it->second) : s.get(PlannerParams{});
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ParamSpecs, TheCfgListsExactlyTheReconfigurableOnesWithTheirTypes) {
  std::set<std::string> in_cfg;
  const std::map<Type, std::string> cfg_type = {{Type::kBool, "bool"},
                                                {Type::kInt, "int"},
                                                {Type::kDouble, "double"},
                                                {Type::kString, "str"}};
  for (const auto& d : AmhaPlannerConfig::__getParamDescriptions__()) {
    in_cfg.insert(d->name);
    const ParamSpec* s = specNamed(d->name);
    ASSERT_NE(s, nullptr) << d->name << " is in the .cfg but not in paramSpecs()";
    EXPECT_TRUE(s->reconfigurable) << d->name << " is in the .cfg but marked start-up only";
    EXPECT_EQ(cfg_type.at(s->type), d->type) << d->name;
  }
  for (const ParamSpec& s : paramSpecs()) {
    if (s.reconfigurable) {
      EXPECT_TRUE(in_cfg.count(s.name)) << s.name << " is not in the .cfg";
    }
  }
  std::set<std::string> names;
  for (const ParamSpec& s : paramSpecs()) EXPECT_TRUE(names.insert(s.name).second) << s.name;
}

TEST(ParamSpecs, TheCfgRangesAndDefaultsAreTheServers) {
  const auto lo = message(AmhaPlannerConfig::__getMin__());
  const auto hi = message(AmhaPlannerConfig::__getMax__());
  const auto def = message(AmhaPlannerConfig::__getDefault__());
  for (const ParamSpec& s : paramSpecs()) {
    if (!s.reconfigurable) continue;
    ParamValue v;
    ASSERT_TRUE(valueIn(def, s.name, &v)) << s.name;
    EXPECT_EQ(v, statedDefault(s)) << s.name << ": the .cfg's default is " << paramText(v)
                                   << ", the server's " << paramText(statedDefault(s));
    if (s.type != Type::kInt && s.type != Type::kDouble) continue;
    ParamValue min, max;
    ASSERT_TRUE(valueIn(lo, s.name, &min) && valueIn(hi, s.name, &max)) << s.name;
    auto number = [](const ParamValue& x) {
      return x.index() == 1 ? std::get<int>(x) : std::get<double>(x);
    };
    EXPECT_EQ(number(min), s.minus_one_is_preset ? -1.0 : s.min) << s.name;
    EXPECT_EQ(number(max), s.max) << s.name;
  }
}

TEST(ParamSpecs, PlannerYamlStatesEveryDefault) {
  const YAML::Node yaml = YAML::LoadFile(std::string(AMHA_SOURCE_DIR) + "/config/planner.yaml");
  std::set<std::string> in_yaml;
  for (const auto& kv : yaml) {
    const std::string name = kv.first.as<std::string>();
    in_yaml.insert(name);
    const ParamSpec* s = specNamed(name);
    ASSERT_NE(s, nullptr) << "config/planner.yaml sets " << name << ", which the server ignores";
    ParamValue v;
    switch (s->type) {
      case Type::kBool:
        v = kv.second.as<bool>();
        break;
      case Type::kInt:
        v = kv.second.as<int>();
        break;
      case Type::kDouble:
        v = kv.second.as<double>();
        break;
      case Type::kString:
        v = kv.second.as<std::string>();
        break;
    }
    EXPECT_EQ(v, statedDefault(*s)) << name << ": the yaml says " << paramText(v)
                                    << ", the server's default is " << paramText(statedDefault(*s));
  }
  // Left out on purpose: a round robot by default; ARA*'s and weighted A*'s presets.
  const std::set<std::string> optional = {"footprint", "eps", "eps_decrement"};
  for (const ParamSpec& s : paramSpecs()) {
    if (!optional.count(s.name)) {
      EXPECT_TRUE(in_yaml.count(s.name)) << s.name << " is not in config/planner.yaml";
    }
  }
}

TEST(ParamSpecs, DocsRosMdDescribesEachOne) {
  const std::string doc = readFile(std::string(AMHA_SOURCE_DIR) + "/docs/ros.md");
  const std::size_t from = doc.find("## Parameters"), to = doc.find("### Changing parameters");
  ASSERT_NE(from, std::string::npos);
  ASSERT_NE(to, std::string::npos);
  const std::string table = doc.substr(from, to - from);
  for (const ParamSpec& s : paramSpecs()) {
    EXPECT_NE(table.find("`" + s.name + "`"), std::string::npos)
        << s.name << " has no row in docs/ros.md's parameter table";
  }
}

// A value other than the default that the server accepts, for each reconfigurable parameter.
ParamValue otherValue(const ParamSpec& s) {
  const std::map<std::string, std::string> texts = {
      {"footprint", "[[0.3, 0.2], [0.3, -0.2], [-0.2, -0.2], [-0.2, 0.2]]"},
      {"mprim_file", "/somewhere/set.json"},
      {"primitive_generator", "legacy"},
      {"motion_model", "ackermann"},
      {"algorithm", "ara"},
      {"inadmissible_heuristics", "paper"},
      {"weight_schedule", "decrement"},
      {"queue_schedule", "dts"}};
  const ParamValue def = s.get(PlannerParams{});
  switch (s.type) {
    case Type::kBool:
      return !std::get<bool>(def);
    case Type::kInt:
      return static_cast<int>(std::get<int>(def) == s.min ? s.max : s.min);
    case Type::kDouble:
      return std::get<double>(def) == s.min ? s.max : s.min;
    case Type::kString:
      break;
  }
  return texts.at(s.name);
}

TEST(ParamSpecs, EachValueReachesItsPlaceAndTheConfiguration) {
  for (const ParamSpec& s : paramSpecs()) {
    if (!s.reconfigurable) continue;
    const ParamValue v = otherValue(s);
    ASSERT_NE(v, s.get(PlannerParams{})) << s.name;
    PlannerParams p;
    ASSERT_EQ(setParam(s, v, &p), "") << s.name << " = " << paramText(v);
    EXPECT_EQ(s.get(p), v) << s.name;
    // Only this parameter changed.
    for (const ParamSpec& other : paramSpecs()) {
      if (other.name != s.name) {
        EXPECT_EQ(other.get(p), other.get(PlannerParams{})) << s.name << " changed " << other.name;
      }
    }
    ParamValue in_config;
    ASSERT_TRUE(valueIn(message(configFromParams(p)), s.name, &in_config)) << s.name;
    EXPECT_EQ(in_config, v) << s.name;
  }
}

TEST(ParamSpecs, SetParamRefusesWhatTheServerCannotUse) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* name;
    ParamValue value;
    const char* problem;
  };
  const Case cases[] = {
      {"default_time_budget", nan, "expected a number"},
      {"w1", 0.5, "neither -1 (the algorithm's preset) nor in [1, 1e+06]"},
      {"w1", std::numeric_limits<double>::infinity(), "expected a number"},
      {"dw1", -2.0, "neither -1"},
      {"robot_radius", -1.0, "is outside [0.001, 10]"},
      {"cost_penalty", 2e4, "is outside [0, 10000]"},
      {"num_headings", 12, "12 is not a multiple of 8"},
      {"anchor_connectivity", 12, "12 is not 8 or 16"},
      {"num_headings", 16.0, "expected an integer"},
      {"grid_anchor", 1, "expected true or false"},
      {"robot_radius", std::string("0.3"), "expected a number"},
      {"algorithm", std::string("dijkstra"), "unknown algorithm 'dijkstra'"},
      {"motion_model", std::string("tank"), "unknown motion model 'tank'"},
      {"queue_schedule", std::string("fifo"), "unknown schedule 'fifo' (rr, dts)"},
      {"footprint", std::string("[[0, 0], [1, 1]]"), "needs at least 3 points"},
      {"footprint", std::string("[[0, 0], [1, 1]"), "unbalanced brackets"},
      {"footprint", std::string("[[0, 0], [1, x], [2, 2]]"), "not a list of [x, y] points"},
      {"global_frame", std::string("/"), "must not be empty"},
  };
  for (const Case& c : cases) {
    const ParamSpec* s = specNamed(c.name);
    ASSERT_NE(s, nullptr) << c.name;
    PlannerParams p;
    const std::string problem = setParam(*s, c.value, &p);
    EXPECT_NE(problem.find(c.problem), std::string::npos)
        << c.name << " = " << paramText(c.value) << ": '" << problem << "'";
    EXPECT_EQ(s->get(p), s->get(PlannerParams{})) << c.name << ": a refused value was stored";
  }
  // What is accepted: -1 for a preset, an integer for a double, a frame's leading '/'.
  PlannerParams p;
  EXPECT_EQ(setParam(*specNamed("dw1"), -1.0, &p), "");
  EXPECT_EQ(setParam(*specNamed("cost_penalty"), 3, &p), "");
  EXPECT_EQ(p.lattice.cost.penalty, 3.0);
  EXPECT_EQ(setParam(*specNamed("global_frame"), std::string("/odom"), &p), "");
  EXPECT_EQ(p.global_frame, "odom");
  EXPECT_EQ(setParam(*specNamed("footprint"), std::string(""), &p), "");
  EXPECT_TRUE(p.lattice.robot.footprint.empty());
}

}  // namespace
}  // namespace amha_planner
