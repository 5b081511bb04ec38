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
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/docs/hal.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR})

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
