// The student-facing assignment contract (docs/design.md): every step's id, lab, position,
// GLSL signature and the other steps its reference solution calls. Each step declares them in
// its own folder, in step.json; the contract is what the step folders declare, nothing more:
// the built-in labs/ first, then every folder added by addStepRoot (out-of-tree steps).
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pbrlab {

struct ContractStep {
    int step = 0;                    // position in the assignment, 1-based (from the order keys)
    std::string id;                  // "ndotl": the student's file is <id>.glsl
    std::string lab;                 // the steps a program links together ("direct", "ibl")
    double order = 0;                // sorts the steps; inserting one changes no other
    std::string function;            // the GLSL signature
    std::vector<std::string> calls;  // ids its reference solution calls
    // Earlier steps whose functions compute what this step asks for another way (step.json
    // "hides"): not linked into this step's programs, and a file of this step that calls one is
    // refused, naming it (vndf_specular hides mc_specular: the same integral, other samples).
    std::vector<std::string> hides;
    // The host's precomputed maps (contract samplers) that hold this step's quantity: a view may
    // read one only when this step comes before its own.
    std::vector<std::string> provides;
    // The pass that computes such a map with this step's reference solution (step.json
    // "precompute"): the host knows how to run a kind of pass, the step says which shader and
    // which sampler. Its sampler is in `provides` too.
    struct PrecomputePass {
        enum class Kind {
            Cube,      // one cube map level: uFace, uSize (the face's side) set per face
            CubeMips,  // a cube map's mips, one draw per mip and face: uRoughness = mip / (mips -
                       // 1)
            Square,    // one 2D texture: uSize (width, height)
        };
        Kind kind = Kind::Cube;
        std::filesystem::path shader;  // a fragment shader in the step folder
        std::string sampler;           // the contract sampler its map is bound to
    };
    std::optional<PrecomputePass> precompute;
    // More pictures of the step in the gallery, besides its default view: on a generated model
    // (assets/models) or a scene (assets/scenes), each one of the two.
    struct GalleryView {
        std::string scene, model;
    };
    std::vector<GalleryView> gallery;
    // Functions the host provides from this step on (step.json "helpers"), each defined in a
    // file of shaders/: split_sum introduces fresnelSchlickRoughness, which its lesson needs
    // and which is Schlick's Fresnel at roughness 0, so no earlier step may call it.
    struct Helper {
        std::string function;  // the GLSL signature
        std::string file;      // in shaders/
    };
    std::vector<Helper> helpers;
    std::filesystem::path folder;  // step.json, solution.glsl, view.glsl, README.md, ...
    // The folder holds starter.glsl and no solution.glsl (solutionWithheld): read once, with
    // step.json, not on every program's recipe.
    bool withheld = false;
    std::string numbered() const;  // "04-ndotl": file names that sort in step order
};

// The steps declared by <root>/*/step.json for each root, in order, numbered. Throws
// pbrlab::Error naming the step.json at fault (a missing field, an id declared twice, two
// steps with one order key, a call to an unknown or later step).
std::vector<ContractStep> readStepFolders(const std::vector<std::filesystem::path>& roots);

// Adds every <root>/*/step.json to the contract (call before the contract is first used, as the
// host does for --modules and $PBRLAB_MODULES). A root without step folders adds nothing.
void addStepRoot(const std::filesystem::path& root);

// The steps of the built-in labs/ and the added roots, in order (readStepFolders).
const std::vector<ContractStep>& contractSteps();

// A contract helper: a function the host provides besides the steps' own (shaders/<file>),
// callable from the step that introduces it on (ContractStep::helpers), in step order.
struct ContractHelper {
    std::string function;      // the GLSL signature
    std::string file;          // the file in shaders/ that defines it
    std::string introducedBy;  // the id of the step whose lesson introduces it
};
std::vector<ContractHelper> contractHelpers();

// The function a GLSL signature declares: "vec3 fresnelSchlick(float cosTheta, vec3 F0)" ->
// "fresnelSchlick".
std::string functionName(const std::string& signature);

// What a step's file may call (docs/design.md, "Assignment contract"): the contract functions
// of its own step and of every earlier step, and the helpers those steps introduce. Everything
// else of the contract is not in its program. The steps a view program links, in step order:
// `step` and every step before it but those it hides.
std::vector<const ContractStep*> stepsVisibleFrom(const ContractStep& step);
// The contract functions and helpers a file of `step` cannot call (those of later steps and of
// the steps it hides), each with what to tell a student who calls one:
// "fresnelSchlickRoughness is introduced in step 21 (split_sum); fresnel cannot call it".
std::map<std::string, std::string> unreachableFrom(const ContractStep& step);

const ContractStep* findContractStep(const std::string& id);
// The step whose quantity the sampler's map holds (step.json "provides"), or nullptr.
const ContractStep* findProvider(const std::string& sampler);

// The contract steps whose GLSL a precompute program for `id` needs (no student's file is in
// it), in step order: every earlier step of the same lab, `extra` ids, and what those call in
// turn.
std::vector<const ContractStep*> contractClosure(const std::string& id,
                                                 const std::vector<std::string>& extra);

// A site built for an assignment (docs/web.md) carries no reference solution of a step whose
// solution is not released: that step's folder holds starter.glsl (the kit's starter file) and
// no solution.glsl. Where a program would link its solution, it links the student's own file of
// the step (<id>.glsl in withheldStepsFolder(): the page's workspace), or the starter while the
// student has none. Installed and source trees withhold nothing.
bool solutionWithheld(const ContractStep& step);
void setWithheldStepsFolder(const std::filesystem::path& folder);
std::filesystem::path withheldStepsFolder();
// The file that defines `step`'s function in a program that links the reference solutions:
// its solution.glsl, or for a withheld step the student's file or the starter.
std::filesystem::path referenceImplementation(const ContractStep& step);

}  // namespace pbrlab
