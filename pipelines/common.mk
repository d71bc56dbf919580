# Rules shared by every pipeline. A case's Makefile sets nothing but includes this file:
#   make -C pipelines/<case>            run every stale stage
#   make -C pipelines/<case> mesh       stop after the mesh (likewise: modes, map)
#   make -C pipelines/<case> clean      remove this case's outputs
# Outputs go to out/<case>/<variant>/ at the repository root. Each stage's command line is
# printed as it runs, so it can be rerun by hand (drop --if-stale to force a rerun).
#
# Staleness is decided by content, not timestamps: every artefact rule is always visited and
# calls its stage with --if-stale, which compares the artefact's provenance (tool version,
# canonical scene parameters of that stage, SHA-256 of every input) with what a run now would
# record, and does nothing when they agree. `touch` on an input reruns nothing; an edited
# material value reruns fsi-modes and what follows, not fsi-mesh.
ROOT     := $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/..)
CASE     ?= $(notdir $(abspath $(CURDIR)))
VARIANT  ?= full
HM_BUILD ?= $(ROOT)/build/release
BIN      := $(HM_BUILD)/stages
OUT      := $(ROOT)/out/$(CASE)/$(VARIANT)
SCENE    := $(abspath scene.toml)

FSI_MESH    := $(BIN)/fsi-mesh/fsi-mesh
FSI_MODES   := $(BIN)/fsi-modes/fsi-modes
FSI_MAP     := $(BIN)/fsi-map/fsi-map
FSI_INSPECT := $(BIN)/fsi-inspect/fsi-inspect

.PHONY: all mesh modes map summary clean FORCE

all: map summary
mesh: $(OUT)/mesh.h5
modes: $(OUT)/modes.h5
map: $(OUT)/mapped.h5

$(OUT)/mesh.h5: FORCE
	@mkdir -p $(OUT)
	$(FSI_MESH) $(SCENE) -o $@ --if-stale

$(OUT)/modes.h5: $(OUT)/mesh.h5 FORCE
	$(FSI_MODES) $(SCENE) --mesh $(OUT)/mesh.h5 -o $@ --if-stale

$(OUT)/mapped.h5: $(OUT)/modes.h5 FORCE
	$(FSI_MAP) $(SCENE) --modes $(OUT)/modes.h5 -o $@ --if-stale

FORCE:

summary: $(OUT)/modes.h5
	@$(FSI_INSPECT) $(OUT)/modes.h5

clean:
	rm -rf $(OUT)
