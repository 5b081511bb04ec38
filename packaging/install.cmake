# What `cmake --install` and `cpack -G DEB` put where (prefix /usr for the
# package): the binaries in bin/, the HAL component where LinuxCNC's
# rtapi_app loads modules (lib/linuxcnc/modules), share/lasercnc (machines,
# examples, register map, HAL configurations, the HMI's translations), the
# systemd unit (its options file, /etc/default/lasercncd, is the
# integrator's: an example in the docs) and the HMI's desktop entry. Installed
# binaries find share/lasercnc from their own folder (core/common/share_path.h).
include(GNUInstallDirs)
install(TARGETS lasercnc lasercncd lasercnc-devices RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
if(TARGET lasercnc-hmi)
  install(TARGETS lasercnc-hmi RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(FILES ${CMAKE_BINARY_DIR}/hmi/i18n/lasercnc_hmi_zh_CN.qm ${CMAKE_BINARY_DIR}/hmi/i18n/lasercnc_hmi_ru.qm
          DESTINATION ${CMAKE_INSTALL_DATADIR}/lasercnc/i18n)
  install(FILES ${CMAKE_CURRENT_LIST_DIR}/lasercnc-hmi.desktop DESTINATION ${CMAKE_INSTALL_DATADIR}/applications)
endif()
if(TARGET lasercnc_hal)
  install(TARGETS lasercnc_hal LIBRARY DESTINATION lib/linuxcnc/modules)
endif()
install(DIRECTORY ${PROJECT_SOURCE_DIR}/share/ DESTINATION ${CMAKE_INSTALL_DATADIR}/lasercnc)
install(FILES ${CMAKE_CURRENT_LIST_DIR}/lasercncd.service DESTINATION lib/systemd/system)
install(FILES ${CMAKE_CURRENT_LIST_DIR}/lasercncd.default DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples
        RENAME default-lasercncd)
# The user's docs placed as in the source tree (README.md, docs/,
# docs/reference/), so the links between them resolve in the installed copy;
# the contributors' docs and the HMI's screenshots stay in the source tree.
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/docs/operator_guide.md ${PROJECT_SOURCE_DIR}/docs/integrator_guide.md
              ${PROJECT_SOURCE_DIR}/docs/process_guide.md ${PROJECT_SOURCE_DIR}/docs/machine_config.md
              ${PROJECT_SOURCE_DIR}/docs/hal.md ${PROJECT_SOURCE_DIR}/docs/laser_cutting.md
              ${PROJECT_SOURCE_DIR}/docs/laser_cutting_plate.svg ${PROJECT_SOURCE_DIR}/docs/spiral_arcs.md
              ${PROJECT_SOURCE_DIR}/docs/design.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
install(FILES ${PROJECT_SOURCE_DIR}/docs/reference/cli.md ${PROJECT_SOURCE_DIR}/docs/reference/gcode.md
              ${PROJECT_SOURCE_DIR}/docs/reference/planner.md ${PROJECT_SOURCE_DIR}/docs/reference/errors.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs/reference)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME lasercnc)
set(CPACK_PACKAGE_VENDOR "LaserCNC")
set(CPACK_PACKAGE_CONTACT "LaserCNC developers <lasercnc@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "PC-based controller for laser machine tools")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# what dpkg-shlibdeps cannot see: QtSql's SQLite driver, a plugin; the
# HMI's fonts, which it names (hmi/hmi_font.h: its screens are laid out in them)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "adduser, libqt5sql5-sqlite, fonts-dejavu-core, fonts-wqy-microhei")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "linuxcnc-uspace")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA ${CMAKE_CURRENT_LIST_DIR}/postinst)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
