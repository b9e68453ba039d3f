#pragma once
/// \file smpl_body_parts.h
/// Part labels, smooth part fields and measurement landmarks for an
/// SMPL-format model a user loads (smpl_model_npz.h), derived from the
/// model's own data: knitforge ships no part segmentation of SMPL (SMPL's
/// own segmentation files are under its non-commercial licence and are
/// neither read nor needed).
///
/// What the model must have: SMPL's 22 body joints by name and tree
/// ("pelvis" .. "right_wrist", SMPL's joint order and parents; SMPL has 24,
/// SMPL+H and SMPL-X 52 and 55 whose first 22 are SMPL's — the loader names
/// them so), standing upright in body_model.h's axes (z up, facing -y, left
/// side +x) in a T-pose-like rest pose (arms out to the sides, as SMPL's
/// templates stand), and every bone used below longer than 1 mm.
///
/// The derivation, on the template, with the rest joints J = regressor x
/// template:
///  - reference lines: the body's coronal plane is the plane through the
///    spine joints (pelvis, spine1..3: their y, interpolated linearly in
///    height), the median plane x = pelvis x;
///  - part fields, each a signed distance (mm) to a plane, or the minimum of
///    several, placed relative to the joints (offsets mostly fractions of
///    the bone lengths, so the cuts follow the body's proportions):
///    head above a plane 22 mm below the head joint (tilted back); neck
///    between that plane and one just below the neck joint, within 1.75
///    times the neck's half-width (at the neck landmark's height) of the
///    median plane; each arm beyond a plane through the shoulder across
///    the upper arm (tilted 8° so the armpit side reaches in further) and
///    above a plane along the upper arm 0.57 upper-arm lengths below the
///    shoulder (cutting off the torso's side); its hand beyond a plane
///    across the forearm just past the wrist, its sleeve the rest; each leg
///    below a plane 10.4 mm above the crotch landmark (below) at the median
///    plane, rising outwards with slope 0.55, on its side of the median
///    plane, its foot below 0.10 shin lengths above the ankle; the torso is
///    the rest, front and back by the coronal plane;
///  - skinning weights keep the limbs apart: a limb's (arm, hand, leg, foot)
///    and the head's field is capped by 1000 mm x (w - 0.02), w the vertex's
///    total weight on the joints of that limb's chain (e.g. collar, shoulder,
///    elbow, wrist and every descendant of the wrist), so a vertex that the
///    limb does not move is never labelled with it, whatever the planes say;
///  - each vertex's label is the part of the largest field;
///  - landmarks (body_measurements.h): the crotch is the lowest vertex
///    near the median plane above the knees; an acromion the highest
///    vertex 2 mm inside to 18 mm outside its shoulder joint (these bands
///    widened, doubling, when a coarse mesh has no vertex in them); the elbow,
///    wrist and upper-arm landmarks the vertices nearest points above those
///    joints (and above mid upper arm); the chest, waist, hip, neck and head
///    landmarks the vertices nearest points far in front of (behind, for the
///    hip) the coronal plane at the heights of spine3, just below spine1,
///    a third of the pelvis-spine1 distance below the pelvis, 0.375 of the
///    way from neck to head and 0.4 of the way from the head joint to the
///    top; thigh and calf the vertices nearest points out to the left of
///    the bones at 0.3 of their length.
/// The constants are those with which our generated body (generated_body.h)
/// places its own cuts, so a body of ours written in SMPL's format gets its
/// own labels back (tests/body/smpl_body_parts_test.cpp measures how
/// closely). Deterministic.

#include <string>

#include "knitforge/body/body_model.h"

namespace knitforge {

/// What label_smpl_body() needs and `model` lacks (missing joints, a tree
/// that is not SMPL's, a degenerate bone, a body that is not upright), as a
/// sentence; empty when the model can be labelled.
std::string smpl_body_parts_missing(const BodyModel& model);

/// Fills model.vertex_parts, part_fields and landmarks (see the file
/// comment) and clears model.labels_note.
/// \throw InvalidInput naming the model and what is missing
///        (smpl_body_parts_missing()), or a part or landmark left without
///        vertices; the model is then unchanged.
void label_smpl_body(BodyModel& model);

}  // namespace knitforge
