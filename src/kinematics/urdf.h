// Serial chains from URDF robot descriptions (read with urdfdom): the joints from a base link
// to a tool link, fixed joints folded in, with messages in our words for every way a file can
// fail to describe an arm.
#pragma once

#include <string>

#include "kinematics/chain.h"

namespace prs::kinematics {

/// The chain from `base_link` to `tool_link` of the URDF document `xml_text`, named
/// `file_label` (used in every message, e.g. the file's path). An empty base_link means the
/// root link; an empty tool_link means the only leaf link below the base. Revolute and
/// prismatic joints keep their limits, continuous joints get [−π, π], fixed joints are folded
/// into the transforms. Thread-safe (urdfdom's logging is captured under a lock; nothing is
/// printed).
///
/// Throws KinematicsError, its message starting with file_label, when the text is not XML or
/// not a URDF (with urdfdom's reason), a named link does not exist (listing the links, with a
/// "did you mean"), the tool link is not below the base link, several leaves could be the tool,
/// a floating, planar or mimic joint lies on the chain, a joint's lower limit is above its upper
/// one or its axis is zero, or the chain has no movable joint.
Chain LoadUrdfChain(const std::string& xml_text, const std::string& file_label,
                    const std::string& base_link = "", const std::string& tool_link = "");

}  // namespace prs::kinematics
