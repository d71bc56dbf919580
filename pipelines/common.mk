# Rules shared by every pipeline. A case's Makefile sets nothing but includes this file:
#   make -C pipelines/<case>            run every stale stage
#   make -C pipelines/<case> mesh       stop after the mesh (likewise: modes, map)
#   make -C pipelines/<case> clean      remove this case's outputs
# Outputs go to out/<case>/<variant>/ at the repository root. Each stage's command line is
# printed as it runs, so it can be rerun by hand.
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

.PHONY: all mesh modes map summary clean
.DELETE_ON_ERROR:

all: map summary
mesh: $(OUT)/mesh.h5
modes: $(OUT)/modes.h5
map: $(OUT)/mapped.h5

$(OUT)/mesh.h5: $(SCENE) $(FSI_MESH)
	@mkdir -p $(OUT)
	$(FSI_MESH) $(SCENE) -o $@

$(OUT)/modes.h5: $(SCENE) $(OUT)/mesh.h5 $(FSI_MODES)
	$(FSI_MODES) $(SCENE) --mesh $(OUT)/mesh.h5 -o $@

$(OUT)/mapped.h5: $(SCENE) $(OUT)/modes.h5 $(FSI_MAP)
	$(FSI_MAP) $(SCENE) --modes $(OUT)/modes.h5 -o $@

summary: $(OUT)/modes.h5
	@$(FSI_INSPECT) $(OUT)/modes.h5

clean:
	rm -rf $(OUT)
