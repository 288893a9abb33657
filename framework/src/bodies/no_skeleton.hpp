#pragma once
// The default BodyModel's refusal of a pose, shared by pose.cpp (which throws
// it) and posed_body.cpp (which tells it from a model's own reason).
namespace drape {
inline constexpr const char* kNoSkeletonRefusal =
    "this body model has no skeleton, so it cannot be posed (it makes unposed bodies only; docs/poses.md)";
}
