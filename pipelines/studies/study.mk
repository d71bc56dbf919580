# Rules shared by the speed-against-error studies. A study's Makefile sets nothing but includes
# this file; its runs are described in study.toml (study.<VARIANT>.toml when it exists):
#   make -C pipelines/studies/<study>           make every stale run, then tabulate and plot
#   make -C pipelines/studies/<study> runs      only make the runs
#   make -C pipelines/studies/<study> table     only tabulate and plot the finished runs
#   make -C pipelines/studies/<study> clean     remove the study's outputs
# Each run is the case's own pipeline (pipelines/<case>) with the run's settings as `--set`
# overrides, in out/studies/<study>/<variant>/<series>/<run>/; staleness is by content as in
# every pipeline, so a rerun of the study only makes what changed. The table and plots go to
# out/studies/<study>/<variant>/study/ (study.md, study.json, <series>.cost.png,
# <series>.curves.png). The wall times are compared, so run the study on a quiet machine; runs
# may go in parallel (make -j2) with OMP_NUM_THREADS=1 each.
ROOT      := $(abspath $(dir $(lastword $(MAKEFILE_LIST)))/../..)
STUDY     ?= $(notdir $(abspath $(CURDIR)))
VARIANT   ?= full
HM_BUILD  ?= $(ROOT)/build/release
FSI_STUDY := $(HM_BUILD)/stages/fsi-study/fsi-study
STUDY_FILE := $(abspath $(firstword $(wildcard study.$(VARIANT).toml) study.toml))
STUDY_OUT ?= $(ROOT)/out/studies/$(STUDY)/$(VARIANT)
RULES     := $(STUDY_OUT)/runs.mk

.PHONY: all runs table clean FORCE
all: table

# The runs as make variables (STUDY_SCENE, STUDY_CASE_DIR, STUDY_RUNS, STUDY_SET.<series>/<run>),
# written by fsi-study from the study file, which it checks with every run's settings first.
include $(RULES)
$(RULES): $(STUDY_FILE) $(FSI_STUDY)
	$(FSI_STUDY) $(STUDY_FILE) --make-rules -o $@

RUN_TARGETS := $(addprefix run/,$(STUDY_RUNS))
.PHONY: $(RUN_TARGETS)
runs: $(RUN_TARGETS)
# A run that diverges (fsi-simulate exits 3 with results.h5 marked "diverged") does not stop the
# study: the table shows its status and its errors up to where it stopped. A run that fails
# otherwise leaves no results.h5, and fsi-study then stops naming it (exit 2).
$(RUN_TARGETS): run/%:
	-$(MAKE) -C $(STUDY_CASE_DIR) --no-print-directory SCENE=$(STUDY_SCENE) \
	  OUT=$(STUDY_OUT)/$* HM_BUILD=$(HM_BUILD) SET="$(STUDY_SET.$*)" simulate

table: $(if $(filter table,$(MAKECMDGOALS)),,runs)
	$(FSI_STUDY) $(STUDY_FILE) --runs $(STUDY_OUT) -o $(STUDY_OUT)/study/study.json
	@cat $(STUDY_OUT)/study/study.md

clean:
	rm -rf $(STUDY_OUT)
