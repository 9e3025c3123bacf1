# Install jointlin for C, Fortran and Abaqus hosts:
#
#   make install PREFIX=/opt/jointlin        # cargo build --release, then install
#   make install PREFIX=... JOINTLIN_LIBDIR=<dir with a built libjointlin.so> \
#                JOINTLIN_BIN=<a built jointlin program>   # install existing builds
#
# installs
#   $(PREFIX)/bin/jointlin                        the harness CLI (scenes, sweeps, studies)
#   $(PREFIX)/lib/libjointlin.so.$(VERSION)       the C API (cargo's cdylib), stripped;
#   $(PREFIX)/lib/libjointlin.so.$(ABI_MAJOR)     its SONAME, a link to it;
#   $(PREFIX)/lib/libjointlin.so                  the link -ljointlin finds
#   $(PREFIX)/lib/.debug/libjointlin.so.$(VERSION).debug   its debug info (gdb and perf
#                                                 find it through .gnu_debuglink;
#                                                 DEBUGINFO=no leaves it out)
#   $(PREFIX)/lib/libjointlin_abaqus.a            UINTER, UEXTERNALDB + module code (PIC,
#                                                 gfortran: needs libgfortran.so.5; ranks
#                                                 agree through files, MPI=no)
#   $(PREFIX)/lib/pkgconfig/jointlin.pc           pkg-config --cflags --libs jointlin
#   $(PREFIX)/include/jointlin.h                  the C header
#   $(PREFIX)/include/jointlin.mod, jointlin_abaqus.mod   Fortran modules ($(FC)'s format)
#   $(PREFIX)/share/jointlin/fortran-shim/        shim sources and Makefile, to rebuild
#                                                 with another compiler (its
#                                                 JOINTLIN_LIBDIR defaults to $(PREFIX)/lib)
#   $(PREFIX)/share/jointlin/examples/            C, Fortran and Abaqus examples (the
#                                                 Abaqus env file names $(PREFIX); the
#                                                 pass drivers passes.sh and passes.py)
#   $(PREFIX)/share/jointlin/examples/deck/       the Gmsh bolted lap deck (.geo, deck, mesh;
#                                                 scenes/bolted-lap.toml reads it from there)
#   $(PREFIX)/share/jointlin/scenes/              the scenes (`jointlin validate` finds
#                                                 them there from any directory)
#   $(PREFIX)/share/man/man1/jointlin*.1          man pages of the program and its
#                                                 commands (`jointlin man`, from the help)
#
# The workspace's release profile keeps line-level debug info (profiling); the installed
# library and program are stripped copies (objcopy --strip-unneeded).
CARGO ?= cargo
OBJCOPY ?= objcopy
READELF ?= readelf
PREFIX ?= /usr/local
DESTDIR ?=
DEBUGINFO ?= yes
CARGO_TARGET_DIR ?= target
BUILD ?= $(CARGO_TARGET_DIR)/jointlin-install
.DEFAULT_GOAL := shim
VERSION := $(shell sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)
ABI_MAJOR := $(shell sed -n 's/^pub const JOINTLIN_ABI_VERSION_MAJOR: u32 = \([0-9]*\);/\1/p' src/ffi/mod.rs)
SONAME := libjointlin.so.$(ABI_MAJOR)
REALNAME := libjointlin.so.$(VERSION)

ifdef JOINTLIN_LIBDIR
LIBDIR := $(JOINTLIN_LIBDIR)
lib:
	@test -f $(LIBDIR)/libjointlin.so || { echo "no $(LIBDIR)/libjointlin.so"; exit 1; }
else
LIBDIR := $(CARGO_TARGET_DIR)/release
lib:
	$(CARGO) build --release -p jointlin --lib
endif

ifdef JOINTLIN_BIN
BIN := $(JOINTLIN_BIN)
bin:
	@test -x $(BIN) || { echo "no program $(BIN)"; exit 1; }
else
BIN := $(CARGO_TARGET_DIR)/release/jointlin
bin:
	$(CARGO) build --release -p jointlin-harness --bin jointlin
endif

shim: lib
	$(MAKE) -f fortran-shim/Makefile BUILD=$(abspath $(BUILD))/shim JOINTLIN_LIBDIR=$(abspath $(LIBDIR))

DEST = $(DESTDIR)$(PREFIX)

# $(call stripped,SOURCE,TARGET,DEBUGDIR): TARGET = SOURCE without symbols and debug
# info; with DEBUGINFO=yes the debug info goes to DEBUGDIR/<name>.debug, linked by
# .gnu_debuglink.
define stripped
	install -m 755 $(1) $(2).tmp
	if [ "$(DEBUGINFO)" = yes ]; then \
		install -d $(3) && \
		$(OBJCOPY) --only-keep-debug $(2).tmp $(3)/$(notdir $(2)).debug && \
		chmod 644 $(3)/$(notdir $(2)).debug && \
		$(OBJCOPY) --strip-unneeded --add-gnu-debuglink=$(3)/$(notdir $(2)).debug $(2).tmp; \
	else \
		$(OBJCOPY) --strip-unneeded $(2).tmp; \
	fi
	mv -f $(2).tmp $(2)
endef

install: lib bin shim
	@$(READELF) -d $(LIBDIR)/libjointlin.so | grep -q 'Library soname: \[$(SONAME)\]' || { \
		echo "$(LIBDIR)/libjointlin.so has no SONAME $(SONAME): rebuild it (build.rs sets it)"; \
		exit 1; }
	install -d $(DEST)/bin $(DEST)/lib/pkgconfig $(DEST)/include \
		$(DEST)/share/jointlin/fortran-shim $(DEST)/share/jointlin/examples/c \
		$(DEST)/share/jointlin/examples/fortran $(DEST)/share/jointlin/examples/abaqus \
		$(DEST)/share/jointlin/examples/abaqus/block-on-plane \
		$(DEST)/share/jointlin/examples/abaqus/three-beams \
		$(DEST)/share/jointlin/examples/deck \
		$(DEST)/share/jointlin/scenes $(DEST)/share/man/man1
	$(call stripped,$(BIN),$(DEST)/bin/jointlin,$(DEST)/bin/.debug)
	$(call stripped,$(LIBDIR)/libjointlin.so,$(DEST)/lib/$(REALNAME),$(DEST)/lib/.debug)
	ln -sfn $(REALNAME) $(DEST)/lib/$(SONAME)
	ln -sfn $(SONAME) $(DEST)/lib/libjointlin.so
	install -m 644 $(BUILD)/shim/libjointlin_abaqus.a $(DEST)/lib/
	install -m 644 include/jointlin.h $(BUILD)/shim/jointlin.mod \
		$(BUILD)/shim/jointlin_abaqus.mod $(DEST)/include/
	install -m 644 fortran-shim/jointlin.f90 fortran-shim/jointlin_abaqus.f90 \
		fortran-shim/uinter.f fortran-shim/uexternaldb.f fortran-shim/urdfil.f \
		fortran-shim/agree_nompi.f90 \
		fortran-shim/agree_mpi.f90 fortran-shim/abaqus_standin.f \
		fortran-shim/abaqus_standin_mpi.f90 fortran-shim/shim_check.f90 \
		fortran-shim/ABA_PARAM.INC fortran-shim/README.md \
		$(DEST)/share/jointlin/fortran-shim/
	sed 's|^JOINTLIN_LIBDIR ?= .*|JOINTLIN_LIBDIR ?= $(PREFIX)/lib|' fortran-shim/Makefile \
		> $(DEST)/share/jointlin/fortran-shim/Makefile
	install -m 644 examples/c/hello.c $(DEST)/share/jointlin/examples/c/
	install -m 644 examples/fortran/hello.f90 $(DEST)/share/jointlin/examples/fortran/
	sed 's|/opt/jointlin|$(PREFIX)|g' examples/abaqus/abaqus_v6.env \
		> $(DEST)/share/jointlin/examples/abaqus/abaqus_v6.env
	install -m 644 examples/abaqus/user.f $(DEST)/share/jointlin/examples/abaqus/
	install -m 755 examples/abaqus/passes.sh examples/abaqus/passes.py \
		$(DEST)/share/jointlin/examples/abaqus/
	install -m 644 examples/abaqus/block-on-plane/* \
		$(DEST)/share/jointlin/examples/abaqus/block-on-plane/
	install -m 644 examples/abaqus/three-beams/* \
		$(DEST)/share/jointlin/examples/abaqus/three-beams/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' jointlin.pc.in \
		> $(DEST)/lib/pkgconfig/jointlin.pc
	install -m 644 examples/deck/bolted-lap.geo examples/deck/bolted-lap.inp \
		examples/deck/bolted-lap-mesh.inp $(DEST)/share/jointlin/examples/deck/
	cp -R scenes/. $(DEST)/share/jointlin/scenes/
	$(DEST)/bin/jointlin man --out $(DEST)/share/man/man1 > /dev/null

uninstall:
	rm -f $(DEST)/bin/jointlin $(DEST)/bin/.debug/jointlin.debug \
		$(DEST)/lib/libjointlin.so $(DEST)/lib/$(SONAME) $(DEST)/lib/$(REALNAME) \
		$(DEST)/lib/.debug/$(REALNAME).debug $(DEST)/lib/libjointlin_abaqus.a \
		$(DEST)/lib/pkgconfig/jointlin.pc $(DEST)/include/jointlin.h \
		$(DEST)/include/jointlin.mod $(DEST)/include/jointlin_abaqus.mod
	rm -rf $(DEST)/share/jointlin
	rm -f $(DEST)/share/man/man1/jointlin.1 $(DEST)/share/man/man1/jointlin-*.1

.PHONY: lib bin shim install uninstall
