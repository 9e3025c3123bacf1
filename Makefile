# Install jointlin for C, Fortran and Abaqus hosts:
#
#   make install PREFIX=/opt/jointlin        # cargo build --release, then install
#   make install PREFIX=... JOINTLIN_LIBDIR=<dir with a built libjointlin.so>
#
# installs
#   $(PREFIX)/lib/libjointlin.so                  the C API (cargo's cdylib)
#   $(PREFIX)/lib/libjointlin_abaqus.a            UINTER, UEXTERNALDB + module code (PIC)
#   $(PREFIX)/lib/pkgconfig/jointlin.pc           pkg-config --cflags --libs jointlin
#   $(PREFIX)/include/jointlin.h                  the C header
#   $(PREFIX)/include/jointlin.mod, jointlin_abaqus.mod   Fortran modules ($(FC)'s format)
#   $(PREFIX)/share/jointlin/fortran-shim/        shim sources (to rebuild with another
#                                                 compiler), abaqus_standin.f, examples
CARGO ?= cargo
PREFIX ?= /usr/local
DESTDIR ?=
CARGO_TARGET_DIR ?= target
BUILD ?= $(CARGO_TARGET_DIR)/jointlin-install
.DEFAULT_GOAL := shim
VERSION := $(shell sed -n 's/^version = "\(.*\)"/\1/p' Cargo.toml | head -n 1)

ifdef JOINTLIN_LIBDIR
LIBDIR := $(JOINTLIN_LIBDIR)
lib:
	@test -f $(LIBDIR)/libjointlin.so || { echo "no $(LIBDIR)/libjointlin.so"; exit 1; }
else
LIBDIR := $(CARGO_TARGET_DIR)/release
lib:
	$(CARGO) build --release -p jointlin --lib
endif

shim: lib
	$(MAKE) -f fortran-shim/Makefile BUILD=$(abspath $(BUILD))/shim JOINTLIN_LIBDIR=$(abspath $(LIBDIR))

DEST = $(DESTDIR)$(PREFIX)

install: lib shim
	install -d $(DEST)/lib/pkgconfig $(DEST)/include $(DEST)/share/jointlin/fortran-shim \
		$(DEST)/share/jointlin/examples/c $(DEST)/share/jointlin/examples/fortran \
		$(DEST)/share/jointlin/examples/abaqus
	install -m 755 $(LIBDIR)/libjointlin.so $(DEST)/lib/libjointlin.so
	install -m 644 $(BUILD)/shim/libjointlin_abaqus.a $(DEST)/lib/
	install -m 644 include/jointlin.h $(BUILD)/shim/jointlin.mod \
		$(BUILD)/shim/jointlin_abaqus.mod $(DEST)/include/
	install -m 644 fortran-shim/jointlin.f90 fortran-shim/jointlin_abaqus.f90 \
		fortran-shim/uinter.f fortran-shim/uexternaldb.f fortran-shim/abaqus_standin.f \
		fortran-shim/ABA_PARAM.INC fortran-shim/Makefile fortran-shim/README.md \
		$(DEST)/share/jointlin/fortran-shim/
	install -m 644 examples/c/hello.c $(DEST)/share/jointlin/examples/c/
	install -m 644 examples/fortran/hello.f90 $(DEST)/share/jointlin/examples/fortran/
	install -m 644 examples/abaqus/* $(DEST)/share/jointlin/examples/abaqus/
	sed -e 's|@PREFIX@|$(PREFIX)|' -e 's|@VERSION@|$(VERSION)|' jointlin.pc.in \
		> $(DEST)/lib/pkgconfig/jointlin.pc

uninstall:
	rm -f $(DEST)/lib/libjointlin.so $(DEST)/lib/libjointlin_abaqus.a \
		$(DEST)/lib/pkgconfig/jointlin.pc $(DEST)/include/jointlin.h \
		$(DEST)/include/jointlin.mod $(DEST)/include/jointlin_abaqus.mod
	rm -rf $(DEST)/share/jointlin

.PHONY: lib shim install uninstall
