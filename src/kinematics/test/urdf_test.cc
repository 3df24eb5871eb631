// URDF arms: the toy arm and the six-joint arm load and their forward kinematics match poses
// computed by hand, and every bad file gives a message in our words naming the file and the
// problem (no urdfdom or console_bridge decorations).
#include "kinematics/urdf.h"

#include <gtest/gtest.h>

#include <fstream>
#include <numbers>
#include <set>
#include <sstream>

#include "geometry/random.h"

namespace prs::kinematics {
namespace {

constexpr double kPi = std::numbers::pi;

std::string ReadData(const std::string& name) {
  std::ifstream in(std::string(PRS_KINEMATICS_TEST_DATA) + "/" + name);
  EXPECT_TRUE(in) << name;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The message of the KinematicsError that loading `name` throws.
std::string LoadError(const std::string& name, const std::string& base = "",
                      const std::string& tool = "") {
  try {
    LoadUrdfChain(ReadData(name), name, base, tool);
  } catch (const KinematicsError& e) {
    return e.what();
  }
  ADD_FAILURE() << name << " loaded without an error";
  return "";
}

void ExpectMessage(const std::string& message, const std::string& file,
                   const std::vector<std::string>& parts) {
  EXPECT_EQ(message.rfind(file + ": ", 0), 0u) << message;
  for (const std::string& part : parts) {
    EXPECT_NE(message.find(part), std::string::npos) << "'" << part << "' not in: " << message;
  }
  for (const char* noise : {"console_bridge", "Error:", "Error ", ".cpp", " at line "}) {
    EXPECT_EQ(message.find(noise), std::string::npos) << "'" << noise << "' in: " << message;
  }
}

TEST(UrdfTest, ToyArmMatchesHandComputedPoses) {
  const Chain chain = LoadUrdfChain(ReadData("toy_arm.urdf"), "toy_arm.urdf");
  ASSERT_EQ(chain.num_joints(), 3);
  EXPECT_EQ(chain.joints[1].name, "shoulder");
  EXPECT_EQ(chain.joints[2].lower, -2.5);
  geometry::Rng rng(2, 0);
  for (int trial = 0; trial < 20; ++trial) {
    const double q1 = rng.Uniform(-3, 3), q2 = rng.Uniform(-1.5, 1.5), q3 = rng.Uniform(-2.5, 2.5);
    // In the turntable's plane: 0.3 m upper arm and 0.25 m forearm about y from (0, 0, 0.3).
    const double reach = 0.3 * std::cos(q2) + 0.25 * std::cos(q2 + q3);
    const double height = 0.3 - 0.3 * std::sin(q2) - 0.25 * std::sin(q2 + q3);
    const Eigen::Vector3d expected(reach * std::cos(q1), reach * std::sin(q1), height);
    const Eigen::Isometry3d X = CalcToolPose(chain, Eigen::Vector3d(q1, q2, q3));
    EXPECT_LT((X.translation() - expected).norm(), 1e-12);
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(q1, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(q2 + q3, Eigen::Vector3d::UnitY()))
                                  .toRotationMatrix();
    EXPECT_LT((X.linear() - R).norm(), 1e-12);
  }
}

// The UR5's standard DH product, computed independently of the URDF.
Eigen::Isometry3d CalcUr5Pose(const Eigen::VectorXd& q) {
  const double d[6] = {0.089159, 0, 0, 0.10915, 0.09465, 0.0823};
  const double a[6] = {0, -0.425, -0.39225, 0, 0, 0};
  const double alpha[6] = {kPi / 2, 0, 0, kPi / 2, -kPi / 2, 0};
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 6; ++i) {
    X = X * Eigen::AngleAxisd(q[i], Eigen::Vector3d::UnitZ()) *
        Eigen::Translation3d(a[i], 0, d[i]) * Eigen::AngleAxisd(alpha[i], Eigen::Vector3d::UnitX());
  }
  return X;
}

TEST(UrdfTest, SixJointArmMatchesItsDhParameters) {
  const Chain chain = LoadUrdfChain(ReadData("six_joint_arm.urdf"), "six_joint_arm.urdf");
  ASSERT_EQ(chain.num_joints(), 6);
  EXPECT_EQ(chain.joints[5].name, "wrist_3_joint");
  EXPECT_EQ(chain.joints[5].lower, -kPi);  // continuous
  EXPECT_EQ(chain.joints[5].upper, kPi);
  // At zero, by hand: x = a2 + a3, y = −(d4 + d6), z = d1 − d5.
  const Eigen::Isometry3d X0 = CalcToolPose(chain, Eigen::VectorXd::Zero(6));
  EXPECT_LT((X0.translation() - Eigen::Vector3d(-0.81725, -0.19145, -0.005491)).norm(), 1e-12);
  geometry::Rng rng(4, 0);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd q(6);
    for (int i = 0; i < 6; ++i) q[i] = rng.Uniform(-kPi, kPi);
    EXPECT_LT((CalcToolPose(chain, q).matrix() - CalcUr5Pose(q).matrix()).cwiseAbs().maxCoeff(),
              1e-12);
  }
}

TEST(UrdfTest, NamedBaseAndToolLinksPickASubchain) {
  const Chain chain =
      LoadUrdfChain(ReadData("six_joint_arm.urdf"), "arm", "upper_arm_link", "wrist_2_link");
  ASSERT_EQ(chain.num_joints(), 3);  // elbow, wrist 1, wrist 2
  EXPECT_EQ(chain.joints[0].name, "elbow_joint");
  EXPECT_EQ(chain.joints[2].name, "wrist_2_joint");
  const Chain fingers =
      LoadUrdfChain(ReadData("two_fingers.urdf"), "two_fingers.urdf", "", "left_finger");
  ASSERT_EQ(fingers.num_joints(), 2);
  EXPECT_EQ(fingers.joints[1].type, JointType::kPrismatic);
}

TEST(UrdfTest, NotXml) {
  ExpectMessage(LoadError("not_xml.urdf"), "not_xml.urdf", {"not an XML document", "line"});
}

TEST(UrdfTest, NotAUrdf) {
  ExpectMessage(LoadError("not_urdf.urdf"), "not_urdf.urdf", {"not a URDF", "<scene>"});
}

TEST(UrdfTest, InvalidUrdfGivesUrdfdomsReasonCleaned) {
  ExpectMessage(LoadError("revolute_without_limit.urdf"), "revolute_without_limit.urdf",
                {"not a valid URDF", "swing", "limit"});
}

TEST(UrdfTest, UnknownLinkSuggestsTheNearestName) {
  const std::string message = LoadError("toy_arm.urdf", "", "forarm");
  ExpectMessage(message, "toy_arm.urdf",
                {"no link named 'forarm'", "did you mean 'forearm'?", "'upper_arm'"});
  const std::string base = LoadError("toy_arm.urdf", "bsae", "");
  ExpectMessage(base, "toy_arm.urdf",
                {"no link named 'bsae' (the base link)", "did you mean 'base'?"});
  const std::string far = LoadError("toy_arm.urdf", "", "gripper_tip");
  EXPECT_EQ(far.find("did you mean"), std::string::npos) << far;
}

TEST(UrdfTest, ToolNotDownstreamOfBase) {
  ExpectMessage(LoadError("toy_arm.urdf", "forearm", "upper_arm"), "toy_arm.urdf",
                {"'upper_arm' is not downstream of the base link 'forearm'", "'base'"});
}

TEST(UrdfTest, SeveralLeavesMakeTheToolAmbiguous) {
  ExpectMessage(LoadError("two_fingers.urdf"), "two_fingers.urdf",
                {"2 leaf links", "'left_finger', 'right_finger'", "name the tool link"});
}

TEST(UrdfTest, FloatingJointOnTheChain) {
  ExpectMessage(LoadError("floating_joint.urdf"), "floating_joint.urdf",
                {"joint 'free'", "floating"});
}

TEST(UrdfTest, LowerLimitAboveUpper) {
  ExpectMessage(LoadError("limits_reversed.urdf"), "limits_reversed.urdf",
                {"joint 'elbow'", "lower limit (1.2) above its upper limit (-0.4)"});
}

TEST(UrdfTest, MimicJointOnTheChain) {
  ExpectMessage(LoadError("mimic_joint.urdf"), "mimic_joint.urdf",
                {"joint 'follower' mimics joint 'leader'"});
}

TEST(UrdfTest, TextThatIsNotUtf8) {
  // A text that stops inside a multi-byte character made TinyXML read past its end (found by
  // the fuzzer); a NUL byte would silently cut the document short.
  for (const std::string& text : {std::string("<robot name=\"r\"><link name=\"a\xe9"),
                                  std::string("<robot>\n<link name=\"a\"/>\0</robot>", 31),
                                  std::string("<robot name=\"\xff\"/>")}) {
    try {
      LoadUrdfChain(text, "bytes.urdf");
      FAIL() << "expected an error";
    } catch (const KinematicsError& e) {
      EXPECT_NE(std::string(e.what()).find("bytes.urdf: not UTF-8 text"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(LoadUrdfChain(ReadData("toy_arm.urdf") + "<!-- caf\xc3\xa9 -->", "toy.urdf"));
}

TEST(UrdfTest, JointsThatMakeALoop) {
  // urdfdom accepts a joint from a link to itself; walking such a tree would never end.
  ExpectMessage(LoadError("joint_loop.urdf"), "joint_loop.urdf",
                {"connect the links as a tree", "joint 'j3' makes link 'b' its own child",
                 "closing the loop 'b' -> 'b'"});
}

// A robot of links a, b, c, ... and one revolute joint for each pair in `joints`.
std::string RobotWithJoints(const std::vector<std::pair<std::string, std::string>>& joints) {
  std::string text = "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n";
  std::set<std::string> links;
  for (const auto& [parent, child] : joints) links.insert({parent, child});
  for (const std::string& link : links) text += "  <link name=\"" + link + "\"/>\n";
  for (size_t i = 0; i < joints.size(); ++i) {
    text.append("  <joint name=\"j").append(std::to_string(i + 1));
    text += "\" type=\"revolute\"><parent link=\"" + joints[i].first + "\"/><child link=\"" +
            joints[i].second +
            "\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"1\" "
            "velocity=\"1\"/></joint>\n";
  }
  return text + "</robot>\n";
}

std::string LoadTextError(const std::string& text, const std::string& label) {
  try {
    LoadUrdfChain(text, label);
  } catch (const KinematicsError& e) {
    return e.what();
  }
  ADD_FAILURE() << label << " loaded without an error";
  return "";
}

TEST(UrdfTest, ALoopIsSaidInOurWordsWithTheLinkThatClosesIt) {
  // Every link a child: urdfdom finds no root, and its sentence ("No root link found. The robot
  // xml is not a valid tree.") names no link.
  const std::string loop =
      LoadTextError(RobotWithJoints({{"a", "b"}, {"b", "c"}, {"c", "a"}}), "loop.urdf");
  ExpectMessage(loop, "loop.urdf",
                {"the joints do not connect the links as a tree: joint 'j3' makes link 'a' a "
                 "child of link 'c', which is below it already, closing the loop 'a' -> 'b' -> "
                 "'c' -> 'a'"});
  EXPECT_EQ(loop.find("root"), std::string::npos) << loop;
  EXPECT_EQ(loop.find("valid tree"), std::string::npos) << loop;
  // A loop below a root: the walk starts at the root, and the loop's own links are named.
  const std::string below = LoadTextError(
      RobotWithJoints({{"base", "a"}, {"a", "b"}, {"b", "c"}, {"c", "a"}}), "below.urdf");
  ExpectMessage(below, "below.urdf",
                {"joint 'j4' makes link 'a' a child of link 'c'",
                 "closing the loop 'a' -> 'b' -> 'c' -> 'a'"});
  EXPECT_EQ(below.find("'base' ->"), std::string::npos) << below;
  // Two joints to one child without a loop is not a tree either, and said so.
  ExpectMessage(
      LoadTextError(RobotWithJoints({{"base", "a"}, {"base", "b"}, {"a", "c"}, {"b", "c"}}),
                    "diamond.urdf"),
      "diamond.urdf", {"link 'c' is the child of more than one joint"});
  // A long chain is walked without recursion.
  std::vector<std::pair<std::string, std::string>> chain;
  for (int i = 0; i < 20000; ++i) {
    // Appended, not "l" + std::to_string(...): GCC 12's false -Wrestrict (its bug 105329).
    std::string parent(1, 'l'), child(1, 'l');
    chain.push_back({parent.append(std::to_string(i)), child.append(std::to_string(i + 1))});
  }
  chain.push_back({"l20000", "l5"});
  ExpectMessage(LoadTextError(RobotWithJoints(chain), "long.urdf"), "long.urdf",
                {"joint 'j20001' makes link 'l5' a child of link 'l20000'"});
}

TEST(UrdfTest, ChainWithoutMovableJoint) {
  ExpectMessage(LoadError("no_movable_joint.urdf"), "no_movable_joint.urdf", {"no movable joint"});
}

TEST(UrdfTest, EmptyText) {
  try {
    LoadUrdfChain("", "empty.urdf");
    FAIL() << "expected an error";
  } catch (const KinematicsError& e) {
    ExpectMessage(e.what(), "empty.urdf", {"not an XML document"});
  }
}

}  // namespace
}  // namespace prs::kinematics
