#!/usr/bin/python3
"""A polkit authority that authorizes every request, on the private test bus only.

rtkit-daemon asks polkit before granting real-time priority; a real polkitd would refuse a user
without a local login session (the test's unprivileged user has none). Never run on a real bus.
"""
import dbus
import dbus.service
from dbus.mainloop.glib import DBusGMainLoop
from gi.repository import GLib


class Authority(dbus.service.Object):
    @dbus.service.method("org.freedesktop.PolicyKit1.Authority",
                         in_signature="(sa{sv})sa{ss}us", out_signature="(bba{ss})")
    def CheckAuthorization(self, subject, action_id, details, flags, cancellation_id):
        return (True, False, dbus.Dictionary({}, signature="ss"))


DBusGMainLoop(set_as_default=True)
bus = dbus.SystemBus()
name = dbus.service.BusName("org.freedesktop.PolicyKit1", bus)
Authority(bus, "/org/freedesktop/PolicyKit1/Authority")
GLib.MainLoop().run()
