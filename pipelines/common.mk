# Rules shared by every pipeline. A case's Makefile sets nothing but includes this file:
#   make -C pipelines/<case>            run every stale stage
#   make -C pipelines/<case> mesh       stop after the mesh (likewise: modes, map)
#   make -C pipelines/<case> simulate   the flow: results.h5, probes.csv, snapshots/
#   make -C pipelines/<case> report     plots and error tables of a finished run: report/
#   make -C pipelines/<case> clean      remove this case's outputs
#   make -C pipelines/<case> archive [NAME=tag]   keep modes.h5 in $(ARCHIVE) as <case>[-tag].modes.h5
#   make -C pipelines/<case> archive-list         the archived mode sets: frequencies, provenance
# A scene reuses an archived set with [modes] archived = "<path>": fsi-modes checks that it was
# computed for the scene's fsi-modes keys and mesh and copies it instead of solving.
# Outputs go to out/<case>/<variant>/ at the repository root. Each stage's command line is
# printed as it runs, so it can be rerun by hand (drop --if-stale to force a rerun).
#
# Staleness is decided by content, not timestamps: every artefact rule is always visited and
# calls its stage with --if-stale, which compares the artefact's provenance (tool version,
# canonical scene parameters of that stage, SHA-256 of every input) with what a run now would
# record, and does nothing when they agree. `touch` on an input reruns nothing; an edited
# material value reruns fsi-modes and what follows, not fsi-mesh.
#
# Variants: `make VARIANT=smoke` runs the case's `scene.smoke.toml` when it exists (a complete
# scene, e.g. a coarser dx and a shorter end time for ctest), else `scene.toml`; the default
# variant `full` runs `scene.toml` (or `scene.full.toml`). Each variant has its own outputs.
#
# Overrides: `make SET="fluid.dx=0.005 time.end=0.2" VARIANT=coarse` runs every stage with
# `--set fluid.dx=0.005 --set time.end=0.2` (scene keys; no blanks inside one setting: write
# arrays as [0.0,0.01]). The artefacts record the values used, so changing SET reruns exactly
# the stages whose keys changed; give such a run its own VARIANT (or OUT) to keep the unmodified
# outputs. The speed-against-error studies (pipelines/studies/) are built on this.
#
# Processes: `make NP=4 simulate` runs fsi-simulate as `$(MPIRUN) -np 4 fsi-simulate …`, the
# flow's points spread over 4 MPI processes (flows with prescribed walls; the README's "Over MPI
# processes"). MPIRUN may carry mpirun's options: MPIRUN="mpirun --hostfile hosts" on a cluster,
# MPIRUN="mpirun --oversubscribe" for more processes than cores. NP=1 (the default) runs
# fsi-simulate as one process, without mpirun. The outputs do not depend on NP (to the PPE
# tolerance), so a run at another NP is not stale.
#
# What runs follows the scene: a [structure] section brings mesh → modes → map; a [fluid]
# section brings simulate (on mesh.h5 when there is a structure, else fsi-simulate meshes the
# [[wall]]s itself, as fsi-mesh needs a structure); [[load]]s without a [fluid] bring a
# structure-only simulate on mesh.h5 and modes.h5; a [fluid] with a [structure] a coupled
# simulate on mesh.h5, modes.h5 and mapped.h5.
ROOT     := $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/..)
CASE     ?= $(notdir $(abspath $(CURDIR)))
VARIANT  ?= full
HM_BUILD ?= $(ROOT)/build/release
BIN      := $(HM_BUILD)/stages
OUT      := $(ROOT)/out/$(CASE)/$(VARIANT)
SCENE    := $(abspath $(firstword $(wildcard scene.$(VARIANT).toml) scene.toml))
SET      ?=
SCENE_ARGS := $(SCENE) $(foreach setting,$(SET),--set '$(setting)')
HAS_STRUCTURE := $(shell grep -q '^\[structure\]' $(SCENE) && echo yes)
HAS_FLUID     := $(shell grep -q '^\[fluid\]' $(SCENE) && echo yes)
HAS_LOADS     := $(shell grep -q '^\[\[load\]\]' $(SCENE) && echo yes)
# A structure-only run: [[load]]s on the structure and no [fluid] (fsi-simulate on modes.h5).
STRUCTURE_RUN := $(if $(HAS_FLUID),,$(HAS_LOADS))

FSI_MESH     := $(BIN)/fsi-mesh/fsi-mesh
FSI_MODES    := $(BIN)/fsi-modes/fsi-modes
FSI_MAP      := $(BIN)/fsi-map/fsi-map
FSI_SIMULATE := $(BIN)/fsi-simulate/fsi-simulate
FSI_INSPECT  := $(BIN)/fsi-inspect/fsi-inspect
FSI_REPORT   := $(BIN)/fsi-report/fsi-report
NP     ?= 1
MPIRUN ?= mpirun
SIMULATE_LAUNCH := $(if $(filter-out 1,$(NP)),$(MPIRUN) -np $(NP))

.PHONY: all mesh modes map simulate report summary clean FORCE

SIMULATES := $(or $(HAS_FLUID),$(STRUCTURE_RUN))
all: $(if $(HAS_STRUCTURE),map) $(if $(SIMULATES),simulate) summary $(if $(SIMULATES),report)
mesh: $(OUT)/mesh.h5
modes: $(OUT)/modes.h5
map: $(OUT)/mapped.h5
simulate: $(OUT)/results.h5

$(OUT)/mesh.h5: FORCE
	@mkdir -p $(OUT)
	$(FSI_MESH) $(SCENE_ARGS) -o $@ --if-stale

$(OUT)/modes.h5: $(OUT)/mesh.h5 FORCE
	$(FSI_MODES) $(SCENE_ARGS) --mesh $(OUT)/mesh.h5 -o $@ --if-stale

$(OUT)/mapped.h5: $(OUT)/modes.h5 FORCE
	$(FSI_MAP) $(SCENE_ARGS) --modes $(OUT)/modes.h5 -o $@ --if-stale

# The flow; probes.csv and snapshots/ (ParaView: snapshots/flow.xdmf) land next to results.h5.
# A structure-only run takes the mode set as well (--modes).
# A coupled run (a [fluid] and a [structure]) takes the mapped modes (--mapped) and the mode set
# (--modes: a nonlinear structure model's interface, structure.model).
COUPLED := $(and $(HAS_FLUID),$(HAS_STRUCTURE))
$(OUT)/results.h5: $(if $(HAS_STRUCTURE),$(OUT)/mesh.h5) $(if $(or $(STRUCTURE_RUN),$(COUPLED)),$(OUT)/modes.h5) $(if $(COUPLED),$(OUT)/mapped.h5) FORCE
	@mkdir -p $(OUT)
	$(SIMULATE_LAUNCH) $(FSI_SIMULATE) $(SCENE_ARGS) $(if $(HAS_STRUCTURE),--mesh $(OUT)/mesh.h5) $(if $(or $(STRUCTURE_RUN),$(COUPLED)),--modes $(OUT)/modes.h5) $(if $(COUPLED),--mapped $(OUT)/mapped.h5) -o $@ --if-stale

# The report (fsi-report): every probe against the scene's [[report.compare]] references, the
# structure's response and the run monitors as PNG, the error metrics as metrics.md/.json.
report: $(OUT)/report/metrics.h5
$(OUT)/report/metrics.h5: $(OUT)/results.h5 FORCE
	$(FSI_REPORT) $(SCENE_ARGS) --results $(OUT)/results.h5 -o $@ --if-stale
	@cat $(OUT)/report/metrics.md

# The mode archive (default: archive/modes/ at the repository root).
ARCHIVE ?= $(ROOT)/archive/modes
ARCHIVED := $(ARCHIVE)/$(CASE)$(if $(NAME),-$(NAME)).modes.h5
.PHONY: archive archive-list
archive: $(OUT)/modes.h5
	@mkdir -p $(ARCHIVE)
	cp $(OUT)/modes.h5 $(ARCHIVED).tmp && mv $(ARCHIVED).tmp $(ARCHIVED)
	@echo "archived $(ARCHIVED); reuse it with [modes] archived = \"$(ARCHIVED)\""
archive-list:
	@for f in $(ARCHIVE)/*.modes.h5; do [ -e "$$f" ] || continue; \
	  $(FSI_INSPECT) --json $$f | python3 -c 'import json, sys; d = json.load(sys.stdin); \
	  a = d.get("attributes", d); \
	  print(sys.argv[1], a.get("created_utc"), a.get("tool_version"), \
	        "f [Hz] =", ", ".join(f"{f:.4g}" for f in d["frequencies_hz"]))' "$$f"; done

FORCE:

summary: $(if $(HAS_STRUCTURE),$(OUT)/modes.h5) $(if $(or $(HAS_FLUID),$(STRUCTURE_RUN)),$(OUT)/results.h5)
	@$(foreach artefact,$^,$(FSI_INSPECT) $(artefact);)

clean:
	rm -rf $(OUT)
